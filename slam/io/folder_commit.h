// Atomic creation of an output folder: everything is written into a temporary
// sibling folder, which is renamed onto the final path only when complete, so
// a failed or interrupted run never leaves a folder that looks complete.
#pragma once

#include <string>

#include "slam/io/output_safety.h"

namespace duskmap {

class StagedFolder {
 public:
  // Checks that `final_path` may be written, removes the staging and old
  // folders of killed runs beside it (RemoveStaleSiblings) and creates the
  // temporary sibling "<final>.tmp-<pid>-<n>". An existing `final_path` may be replaced only with
  // `overwrite` and only when `owner` recognises it (CheckMayReplace); the
  // current folder and its parents are never replaced. Throws InputError
  // naming the path otherwise, or when the parent folder is not writable.
  StagedFolder(const std::string& final_path, bool overwrite, const OwnedOutput& owner);
  // Removes the temporary folder unless Commit() succeeded.
  ~StagedFolder();
  StagedFolder(const StagedFolder&) = delete;
  StagedFolder& operator=(const StagedFolder&) = delete;

  const std::string& staging_path() const { return staging_path_; }
  const std::string& final_path() const { return final_path_; }
  // Puts the staging folder in place of final_path (PublishFolder): without
  // `overwrite` only while the name is free, so a folder that appeared
  // meanwhile is never replaced; with it, an old folder is renamed aside
  // ("<final>.old-<pid>-<n>"), tested by `owner`, and removed once the new
  // one is in place; if it is not owned or the swap fails it is put back.
  void Commit();

 private:
  std::string final_path_;
  std::string staging_path_;
  bool overwrite_ = false;
  OwnedOutput owner_;
  bool committed_ = false;
};

// Creates a folder (and parents); throws InputError naming it when impossible.
void CreateFolder(const std::string& path);

}  // namespace duskmap
