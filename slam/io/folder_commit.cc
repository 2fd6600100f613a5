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
  SLAM_THROW_IF_NOT(InputError, !error && fs::is_directory(path))
      << path << ": cannot create folder (" << (error ? error.message() : "not a folder") << ")";
}

StagedFolder::StagedFolder(const std::string& final_path, bool overwrite)
    : final_path_(fs::path(final_path).lexically_normal().string()), overwrite_(overwrite) {
  SLAM_THROW_IF_NOT(InputError, !final_path_.empty()) << "output folder name is empty";
  if (final_path_.size() > 1 && final_path_.back() == '/') final_path_.pop_back();
  std::error_code error;
  const bool exists = fs::exists(final_path_, error);
  SLAM_THROW_IF_NOT(InputError, !exists || overwrite)
      << final_path_ << ": already exists (use --overwrite to replace it)";
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
  std::error_code error;
  if (fs::exists(final_path_, error)) {
    SLAM_THROW_IF_NOT(InputError, overwrite_)
        << final_path_ << ": already exists (use --overwrite to replace it)";
    fs::remove_all(final_path_, error);
    SLAM_THROW_IF_NOT(InputError, !error)
        << final_path_ << ": cannot remove the old folder (" << error.message() << ")";
  }
  fs::rename(staging_path_, final_path_, error);
  SLAM_THROW_IF_NOT(InputError, !error)
      << final_path_ << ": cannot rename " << staging_path_ << " into place (" << error.message()
      << ")";
  committed_ = true;
}

}  // namespace duskmap
