// What a command may write, and how: the one place every `duskmap` command
// checks its outputs before it writes anything.
//
// - An output is never one of the command's inputs and never lies inside one
//   (`localize --trajectory M.db`, `map --output <dataset>/manifest.json`).
// - An existing output is replaced only with --overwrite, and only when it is
//   something duskmap wrote itself, recognised by its marker (a dataset's
//   manifest.json, a results folder's run.json, a map's schema).
// - Labels taken from configs become one path component, never a path.
// - A results folder is locked while a process writes it.
// - A file is written beside its final path and renamed onto it when
//   complete: a failed write leaves the old file (or none), never a
//   truncated one. Without --overwrite the final name is taken only if it
//   is still free (io/publish.h), so nothing that appears meanwhile is lost.
#pragma once

#include <cstddef>
#include <filesystem>
#include <functional>
#include <ostream>
#include <string>
#include <vector>

#include "slam/io/named_path.h"

namespace duskmap {

// NamedPath and OwnedOutput: io/named_path.h.

// True when `path` is `folder` or lies inside it (after resolving symbolic
// links and "..", for the parts that exist).
bool IsSameOrInside(const std::filesystem::path& path, const std::filesystem::path& folder);

// Throws InputError when an output is, or lies inside, one of the inputs, or
// when two outputs are the same path. Empty paths are ignored.
void CheckOutputsApartFromInputs(const std::vector<NamedPath>& outputs,
                                 const std::vector<NamedPath>& inputs);

// Checks that `path` may be written: absent, or present with `overwrite` and
// recognised by `owner`. Throws InputError naming the path otherwise.
void CheckMayReplace(const NamedPath& output, bool overwrite, const OwnedOutput& owner);

// The markers duskmap leaves. A synthetic dataset: a folder whose
// manifest.json says "format": "duskmap-synthetic". A results folder: a
// folder with run.json (of `duskmap run`). (A map is recognised by the map
// module: IsDuskmapMapFile in slam/map/map_store.h.)
bool IsDuskmapDatasetFolder(const std::filesystem::path& path);
bool IsDuskmapResultsFolder(const std::filesystem::path& path);
OwnedOutput OwnedDataset();
OwnedOutput OwnedResultsFolder();

// The longest label CheckPathLabel accepts: a file name's 255 bytes (NAME_MAX)
// less the ".partial" a job's folder carries while it is written
// (slam/experiment/job_runner.cc). A 48-session map label such as
// "a1+a2+...+h6" takes 143 bytes.
inline constexpr std::size_t kMaxPathLabelBytes = 255 - 8;

// Throws ConfigError("<where>: <label> ...") unless `label` can be used as a
// single path component: non-empty, at most kMaxPathLabelBytes, no '/', '\\'
// or control characters, not "." or "..", not starting with '.'.
void CheckPathLabel(const std::string& label, const std::string& where);

// An exclusive advisory lock (flock) on `<folder>/.duskmap.lock`, held until
// destruction or process exit. A second process gets InputError naming the
// folder and the pid that holds it. The lock file stays (removing it would
// race with a process about to lock it).
class FolderLock {
 public:
  explicit FolderLock(const std::filesystem::path& folder);
  ~FolderLock();
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;

  static constexpr const char* kFileName = ".duskmap.lock";

 private:
  int fd_ = -1;
};

// Writes `path` through `write` into "<path>.partial-<pid>-<n>", flushes it to
// disk and renames it onto `path`, replacing any file there (io/publish.h:
// WriteAndPublish with ReplaceAnyFile; user-named outputs that --overwrite
// guards are published with their own PublishTarget). On any failure (the
// stream's error state, a full disk, an exception from `write`) the partial
// file is removed and InputError names `path` and the system's reason; an
// existing file at `path` is left as it was.
void WriteFileAtomically(const std::string& path, const std::function<void(std::ostream&)>& write);

// The same for writers that need a file name (HDF5): `write` creates and
// closes the file at the partial path it is given; it is then flushed to
// disk and renamed onto `path`. An exception from `write` removes the partial
// file and propagates; a failed flush or rename is an InputError naming
// `path`. An existing file at `path` is left as it was on any failure.
void WriteFileAtomicallyAt(const std::string& path,
                           const std::function<void(const std::string& partial_path)>& write);

}  // namespace duskmap
