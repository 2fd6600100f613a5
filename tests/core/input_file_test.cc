#include "slam/core/input_file.h"

#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "tests/testing/error_of.h"
#include "tests/testing/temp_dir.h"

namespace duskmap {
namespace {
namespace fs = std::filesystem;

std::string ErrorOf(const std::string& path, const std::string& flag = "") {
  return testing::ErrorOf([&] { RefuseNonRegularFile(path, flag); });
}

TEST(RefuseNonRegularFile, RegularFilesAndMissingPathsPass) {
  const std::string file = testing::ProcessTempPath("input_file_regular.json");
  std::ofstream(file) << "{}";
  EXPECT_EQ(ErrorOf(file), "");
  const std::string link = testing::ProcessTempPath("input_file_link.json");
  fs::create_symlink(file, link);
  EXPECT_EQ(ErrorOf(link), "");  // symlinks are followed
  EXPECT_EQ(ErrorOf(testing::ProcessTempPath("input_file_missing.json")), "");  // the reader names it
  EXPECT_EQ(ErrorOf(file + "/below"), "");  // a file on the way: missing too (ENOTDIR)
}

TEST(RefuseNonRegularFile, OtherTypesAreNamed) {
  const std::string fifo = testing::ProcessTempPath("input_file_fifo");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_EQ(ErrorOf(fifo), fifo + ": is a FIFO (named pipe), not a regular file");
  EXPECT_EQ(ErrorOf(fifo, "--map"), "--map " + fifo + ": is a FIFO (named pipe), not a regular file");
  const std::string folder = testing::ProcessTempDir("input_file_folder");
  fs::create_directories(folder);
  EXPECT_EQ(ErrorOf(folder), folder + ": is a folder, not a regular file");
  EXPECT_EQ(ErrorOf("/dev/null"), "/dev/null: is a character device, not a regular file");
}

TEST(RefuseNonRegularFile, OtherFailuresGiveTheSystemsReason) {
  const std::string loop = testing::ProcessTempPath("input_file_loop");
  fs::create_symlink(loop, loop);
  EXPECT_EQ(ErrorOf(loop), loop + ": Too many levels of symbolic links");
}

}  // namespace
}  // namespace duskmap
