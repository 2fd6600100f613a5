#include "slam/io/folder_commit.h"

#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "slam/core/check.h"
#include "tests/testing/temp_dir.h"

namespace duskmap {
namespace {
namespace fs = std::filesystem;

using testing::ProcessTempDir;

TEST(StagedFolder, CommitRenamesIntoPlace) {
  const fs::path root = ProcessTempDir("commit_commit");
  const std::string final_path = (root / "out").string();
  {
    StagedFolder staged(final_path, false, OwnedDataset());
    std::ofstream(staged.staging_path() + "/file.txt") << "x";
    EXPECT_FALSE(fs::exists(final_path));  // nothing visible before the commit
    staged.Commit();
  }
  EXPECT_TRUE(fs::exists(final_path + "/file.txt"));
  EXPECT_EQ(std::distance(fs::directory_iterator(root), fs::directory_iterator()), 1);
}

TEST(StagedFolder, FailureBeforeCommitLeavesNothing) {
  const fs::path root = ProcessTempDir("commit_abort");
  const std::string final_path = (root / "out").string();
  try {
    StagedFolder staged(final_path, false, OwnedDataset());
    std::ofstream(staged.staging_path() + "/half.txt") << "x";
    throw InputError("simulated failure");
  } catch (const InputError&) {
  }
  EXPECT_FALSE(fs::exists(final_path));
  EXPECT_TRUE(fs::is_empty(root));
}

TEST(StagedFolder, ExistingFolderNeedsOverwrite) {
  const fs::path root = ProcessTempDir("commit_exists");
  const std::string final_path = (root / "out").string();
  fs::create_directories(final_path);
  std::ofstream(final_path + "/old.txt") << "old";
  std::ofstream(final_path + "/manifest.json") << R"({"format": "duskmap-synthetic"})";
  try {
    StagedFolder staged(final_path, false, OwnedDataset());
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("already exists"), std::string::npos);
  }
  StagedFolder staged(final_path, true, OwnedDataset());
  std::ofstream(staged.staging_path() + "/new.txt") << "new";
  staged.Commit();
  EXPECT_FALSE(fs::exists(final_path + "/old.txt"));
  EXPECT_TRUE(fs::exists(final_path + "/new.txt"));
}

TEST(StagedFolder, UnwritableParentThrows) {
  if (::geteuid() == 0) GTEST_SKIP() << "running as root: permissions are not enforced";
  const fs::path root = ProcessTempDir("commit_readonly");
  ::chmod(root.c_str(), 0555);
  EXPECT_THROW(StagedFolder((root / "out").string(), false, OwnedDataset()), InputError);
  ::chmod(root.c_str(), 0755);
}

TEST(StagedFolder, ParentIsAFileThrows) {
  const fs::path root = ProcessTempDir("commit_file_parent");
  std::ofstream((root / "plain").string()) << "x";
  EXPECT_THROW(StagedFolder((root / "plain" / "out").string(), false, OwnedDataset()), InputError);
}

TEST(StagedFolder, OverwriteRefusesWhatDuskmapDidNotWrite) {
  const fs::path root = ProcessTempDir("commit_foreign");
  const std::string final_path = (root / "mine").string();
  fs::create_directories(final_path);
  std::ofstream(final_path + "/thesis.tex") << "years of work";
  try {
    StagedFolder staged(final_path, true, OwnedDataset());
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(final_path + ": not a duskmap dataset"), std::string::npos)
        << e.what();
  }
  EXPECT_TRUE(fs::exists(final_path + "/thesis.tex"));
  EXPECT_EQ(std::distance(fs::directory_iterator(root), fs::directory_iterator()), 1);
  // A plain file in the way is not replaced either.
  const std::string file_path = (root / "notes.txt").string();
  std::ofstream(file_path) << "notes";
  EXPECT_THROW(StagedFolder(file_path, true, OwnedDataset()), InputError);
  EXPECT_TRUE(fs::is_regular_file(file_path));
}

// A run killed while it wrote (its process gone) left its staging folder:
// the next staged write of the same output removes it; a live process's is
// kept.
TEST(StagedFolder, StagingFolderOfAKilledRunIsRemoved) {
  const fs::path root = ProcessTempDir("commit_stale");
  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  int status = 0;
  ::waitpid(child, &status, 0);
  const fs::path stale = root / ("out.tmp-" + std::to_string(child));
  const fs::path live = root / ("out.tmp-" + std::to_string(::getppid()) + "-0");
  fs::create_directories(stale / "half");
  fs::create_directories(live);
  {
    StagedFolder staged((root / "out").string(), false, OwnedDataset());
    EXPECT_FALSE(fs::exists(stale));
    EXPECT_TRUE(fs::exists(live));
    staged.Commit();
  }
  EXPECT_TRUE(fs::is_directory(root / "out"));
}

TEST(StagedFolder, NeverReplacesTheCurrentFolderOrItsParents) {
  const fs::path root = ProcessTempDir("commit_cwd");
  const fs::path inner = root / "work";
  fs::create_directories(inner);
  std::ofstream((root / "manifest.json").string()) << R"({"format": "duskmap-synthetic"})";
  std::ofstream((inner / "manifest.json").string()) << R"({"format": "duskmap-synthetic"})";
  const fs::path before = fs::current_path();
  fs::current_path(inner);
  EXPECT_THROW(StagedFolder(".", true, OwnedDataset()), InputError);
  EXPECT_THROW(StagedFolder("..", true, OwnedDataset()), InputError);
  fs::current_path(before);
  EXPECT_TRUE(fs::exists(inner / "manifest.json"));
}

}  // namespace
}  // namespace duskmap
