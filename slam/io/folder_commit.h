// Atomic creation of an output folder: everything is written into a temporary
// sibling folder, which is renamed onto the final path only when complete, so
// a failed or interrupted run never leaves a folder that looks complete.
#pragma once

#include <string>

namespace duskmap {

class StagedFolder {
 public:
  // Checks that `final_path` may be written (absent, or present with
  // overwrite) and creates the temporary sibling "<final>.tmp-<pid>". Throws
  // InputError naming the path when it exists without overwrite or when the
  // parent folder is not writable.
  StagedFolder(const std::string& final_path, bool overwrite);
  // Removes the temporary folder unless Commit() succeeded.
  ~StagedFolder();
  StagedFolder(const StagedFolder&) = delete;
  StagedFolder& operator=(const StagedFolder&) = delete;

  const std::string& staging_path() const { return staging_path_; }
  const std::string& final_path() const { return final_path_; }
  // Replaces final_path by the staging folder (rename in the same parent).
  void Commit();

 private:
  std::string final_path_;
  std::string staging_path_;
  bool overwrite_ = false;
  bool committed_ = false;
};

// Creates a folder (and parents); throws InputError naming it when impossible.
void CreateFolder(const std::string& path);

}  // namespace duskmap
