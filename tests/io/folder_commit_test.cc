#include "slam/io/folder_commit.h"

#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "slam/core/check.h"

namespace duskmap {
namespace {
namespace fs = std::filesystem;

fs::path TempRoot(const std::string& name) {
  const fs::path root = fs::temp_directory_path() / ("duskmap_commit_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(root);
  fs::create_directories(root);
  return root;
}

TEST(StagedFolder, CommitRenamesIntoPlace) {
  const fs::path root = TempRoot("commit");
  const std::string final_path = (root / "out").string();
  {
    StagedFolder staged(final_path, false);
    std::ofstream(staged.staging_path() + "/file.txt") << "x";
    EXPECT_FALSE(fs::exists(final_path));  // nothing visible before the commit
    staged.Commit();
  }
  EXPECT_TRUE(fs::exists(final_path + "/file.txt"));
  EXPECT_EQ(std::distance(fs::directory_iterator(root), fs::directory_iterator()), 1);
}

TEST(StagedFolder, FailureBeforeCommitLeavesNothing) {
  const fs::path root = TempRoot("abort");
  const std::string final_path = (root / "out").string();
  try {
    StagedFolder staged(final_path, false);
    std::ofstream(staged.staging_path() + "/half.txt") << "x";
    throw InputError("simulated failure");
  } catch (const InputError&) {
  }
  EXPECT_FALSE(fs::exists(final_path));
  EXPECT_TRUE(fs::is_empty(root));
}

TEST(StagedFolder, ExistingFolderNeedsOverwrite) {
  const fs::path root = TempRoot("exists");
  const std::string final_path = (root / "out").string();
  fs::create_directories(final_path);
  std::ofstream(final_path + "/old.txt") << "old";
  try {
    StagedFolder staged(final_path, false);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("already exists"), std::string::npos);
  }
  StagedFolder staged(final_path, true);
  std::ofstream(staged.staging_path() + "/new.txt") << "new";
  staged.Commit();
  EXPECT_FALSE(fs::exists(final_path + "/old.txt"));
  EXPECT_TRUE(fs::exists(final_path + "/new.txt"));
}

TEST(StagedFolder, UnwritableParentThrows) {
  if (::geteuid() == 0) GTEST_SKIP() << "running as root: permissions are not enforced";
  const fs::path root = TempRoot("readonly");
  ::chmod(root.c_str(), 0555);
  EXPECT_THROW(StagedFolder((root / "out").string(), false), InputError);
  ::chmod(root.c_str(), 0755);
}

TEST(StagedFolder, ParentIsAFileThrows) {
  const fs::path root = TempRoot("file_parent");
  std::ofstream((root / "plain").string()) << "x";
  EXPECT_THROW(StagedFolder((root / "plain" / "out").string(), false), InputError);
}

}  // namespace
}  // namespace duskmap
