// Publishing an output under its final name without a race: every output a
// command writes is made complete under a temporary sibling name in the
// destination folder and then given its final name in one step.
//
// - Without --overwrite the final name is taken with an operation that fails
//   when the name exists (renameat2 RENAME_NOREPLACE, or link(2) where the
//   filesystem refuses that flag), so a file or folder that appeared at the
//   path while the command ran (another run into the same path, a user's
//   notes) is never replaced: the command fails naming the path.
// - With --overwrite the owner test (OwnedOutput) is made again right before
//   the replace, and a file is replaced atomically (rename); a folder is
//   first moved aside, checked, then replaced, and put back when it is not
//   the command's to replace.
// - A killed command leaves at most its temporary sibling, named with its
//   pid; the next command writing the same path removes the ones whose
//   process is gone (RemoveStaleSiblings).
#pragma once

#include <functional>
#include <ostream>
#include <string>

#include "slam/io/named_path.h"

namespace duskmap {

// Where a finished output goes and what may be replaced there.
struct PublishTarget {
  NamedPath output;  // the final path and the flag that named it (for messages)
  // false: the name must be free when the output is published.
  bool overwrite = false;
  // With `overwrite`: what may be replaced. An empty is_owned replaces any
  // file (outputs documented as replaced every run, e.g. localize's records).
  OwnedOutput owner;
};

// Replaces any file at `path` that is not a folder: what WriteFileAtomically
// does (job files, run.json, localize's records).
PublishTarget ReplaceAnyFile(const std::string& path);

// "<folder>/<name>.<tag>-<pid>-<n>", unique within this process.
std::string TemporarySiblingOf(const std::string& path, const std::string& tag);

// Removes the siblings of `path` named "<name>.<tag>-<pid>" or
// "<name>.<tag>-<pid>-<n>" (files or folders) whose process is no longer
// running: what a killed command left. Returns how many were removed; never
// throws (a sibling that cannot be removed is left).
int RemoveStaleSiblings(const std::string& path, const std::string& tag);

// A folder that PublishFolder moved aside ("<name>.old-<pid>-<n>") and
// whose process was killed before it finished: put back at `path` when
// nothing is there (the new one never arrived), else removed (it was
// replaced). Never throws.
void RecoverStaleAside(const std::string& path);

// Gives the complete file `temp_path` (a sibling of target.output.path) its
// final name, after flushing it to disk. On failure the temporary file is
// removed and InputError names the path: a file that appeared meanwhile
// ("appeared while this command ran; nothing was replaced"), or one that
// --overwrite may not replace; what is at the path is left as it was.
void PublishFile(const std::string& temp_path, const PublishTarget& target);

// The same for a complete folder `staging_path`. A folder already at the
// path is replaced only with `overwrite` and when `owner` recognises it
// (tested after it has been moved aside, so nothing can slip in between).
// On failure the staging folder is kept (its owner removes it) and what was
// at the path is there again.
void PublishFolder(const std::string& staging_path, const PublishTarget& target);

// Writes through `write` into a temporary sibling and publishes it. An
// exception from `write` removes the temporary file and propagates.
void WriteAndPublishAt(const PublishTarget& target,
                       const std::function<void(const std::string& temp_path)>& write);
// The same for a writer of bytes; a failed write (a full disk) is an
// InputError naming the path and the system's reason.
void WriteAndPublish(const PublishTarget& target, const std::function<void(std::ostream&)>& write);

// Test-only: called with the final path right before each publish (the
// output complete under its temporary name), so that a test can make a file
// appear there. `duskmap` installs one from DUSKMAP_TEST_BEFORE_PUBLISH.
using BeforePublishHook = std::function<void(const std::string& final_path)>;
void SetBeforePublishHookForTesting(BeforePublishHook hook);

}  // namespace duskmap
