#include "slam/io/folder_commit.h"

#include <unistd.h>

#include <filesystem>
#include <system_error>

#include "slam/core/check.h"
#include "slam/io/publish.h"

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
  // What a killed run left beside the output: its staging folder, and an
  // old folder it had moved aside (put back when the new one never came).
  RemoveStaleSiblings(final_path_, "tmp");
  RecoverStaleAside(final_path_);
  CheckMayReplace({"--output", final_path_}, overwrite, owner);
  fs::path parent = fs::path(final_path_).parent_path();
  if (parent.empty()) parent = ".";
  CreateFolder(parent.string());
  SLAM_THROW_IF_NOT(InputError, ::access(parent.c_str(), W_OK) == 0)
      << parent.string() << ": output folder is not writable";
  staging_path_ = TemporarySiblingOf(final_path_, "tmp");
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
  // Without overwrite_ the final name is taken only while it is free; with
  // it, what is there is tested again (moved aside first) right before the
  // replace (io/publish.h).
  PublishFolder(staging_path_, {{"--output", final_path_}, overwrite_, owner_});
  committed_ = true;
}

}  // namespace duskmap
