#include "slam/io/folder_commit.h"

#include <unistd.h>

#include <filesystem>
#include <system_error>

#include "slam/core/check.h"

namespace duskmap {
namespace fs = std::filesystem;

void CreateFolder(const std::string& path) {
  std::error_code error;
  fs::create_directories(path, error);
  SLAM_THROW_IF_NOT(InputError, !error && fs::is_directory(path, error))
      << path << ": cannot create folder (" << (error ? error.message() : "not a folder") << ")";
}

StagedFolder::StagedFolder(const std::string& final_path, bool overwrite, const OwnedOutput& owner)
    : final_path_(fs::path(final_path).lexically_normal().string()),
      overwrite_(overwrite),
      owner_(owner) {
  SLAM_THROW_IF_NOT(InputError, !final_path_.empty()) << "output folder name is empty";
  if (final_path_.size() > 1 && final_path_.back() == '/') final_path_.pop_back();
  std::error_code error;
  const fs::path cwd = fs::current_path(error);
  SLAM_THROW_IF_NOT(InputError, error || !IsSameOrInside(cwd, final_path_))
      << final_path << ": is the current folder or one of its parents; choose another output";
  CheckMayReplace({"--output", final_path_}, overwrite, owner);
  fs::path parent = fs::path(final_path_).parent_path();
  if (parent.empty()) parent = ".";
  CreateFolder(parent.string());
  SLAM_THROW_IF_NOT(InputError, ::access(parent.c_str(), W_OK) == 0)
      << parent.string() << ": output folder is not writable";
  staging_path_ = final_path_ + ".tmp-" + std::to_string(::getpid());
  fs::remove_all(staging_path_, error);
  CreateFolder(staging_path_);
}

StagedFolder::~StagedFolder() {
  if (committed_) return;
  std::error_code error;
  fs::remove_all(staging_path_, error);
}

void StagedFolder::Commit() {
  SLAM_CHECK(!committed_);
  // Checked again: something may have appeared at the path while we wrote.
  CheckMayReplace({"--output", final_path_}, overwrite_, owner_);
  std::error_code error;
  const std::string old_path = final_path_ + ".old-" + std::to_string(::getpid());
  const bool had_old = fs::exists(fs::symlink_status(final_path_, error));
  if (had_old) {
    fs::remove_all(old_path, error);
    fs::rename(final_path_, old_path, error);
    SLAM_THROW_IF_NOT(InputError, !error)
        << final_path_ << ": cannot move the old folder aside (" << error.message() << ")";
  }
  fs::rename(staging_path_, final_path_, error);
  if (error) {
    std::error_code restore;
    if (had_old) fs::rename(old_path, final_path_, restore);
    SLAM_THROW(InputError) << final_path_ << ": cannot rename " << staging_path_
                           << " into place (" << error.message() << "); the old folder is "
                           << (had_old && !restore ? "unchanged" : "at " + old_path);
  }
  committed_ = true;
  if (had_old) fs::remove_all(old_path, error);
}

}  // namespace duskmap
