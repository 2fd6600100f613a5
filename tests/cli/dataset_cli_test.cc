// End-to-end tests of `duskmap dataset info`.
#include <gtest/gtest.h>
#include <sqlite3.h>

#include <filesystem>
#include <memory>
#include <string>

#include "tests/testing/temp_dir.h"
#include "tests/testing/run_duskmap.h"

namespace {

using Result = duskmap::testing::CliResult;
using duskmap::testing::RunDuskmap;

std::string RtabmapDir() {
  const std::filesystem::path dir = std::filesystem::path(DUSKMAP_SHARED_DIR) / "data" / "rtabmap";
  return std::filesystem::is_directory(dir) ? dir.string() : "";
}

TEST(DatasetInfo, DescribesAnRtabmapDatabase) {
  const std::string dir = RtabmapDir();
  if (dir.empty()) GTEST_SKIP() << "shared RTAB-Map fixtures not found; skipping";
  const Result r = RunDuskmap("dataset info " + dir + "/rtabmap-db/merged_two_sessions.db");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("format   rtabmap-db"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("sessions 2"), std::string::npos);
  EXPECT_NE(r.output.find("session merged_two_sessions.map1"), std::string::npos);
  EXPECT_NE(r.output.find("resolution:   320x240"), std::string::npos);
  EXPECT_NE(r.output.find("ground truth: yes (10 frames)"), std::string::npos);
  EXPECT_NE(r.output.find("total frames 20"), std::string::npos);
}

TEST(DatasetInfo, DescribesAnImageExport) {
  const std::string dir = RtabmapDir();
  if (dir.empty()) GTEST_SKIP() << "shared RTAB-Map fixtures not found; skipping";
  const Result r = RunDuskmap("dataset info " + dir + "/rtabmap-export --dataset-format rtabmap-images");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("format   rtabmap-images"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("depth range:  1.959 - 3.194 m"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("time span:    1700000000.000000 - 1700000000.900000 s (0.900 s)"),
            std::string::npos);
  EXPECT_NE(r.output.find("ground truth: no"), std::string::npos);
}

TEST(DatasetInfo, BadInputIsAOneLineErrorAndExitCodeOne) {
  const Result missing = RunDuskmap("dataset info /nonexistent/folder");
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_EQ(missing.output, "duskmap: error: /nonexistent/folder: no such file or folder\n");
  const Result format = RunDuskmap("dataset info /tmp --dataset-format colmap");
  EXPECT_EQ(format.exit_code, 1);
  EXPECT_NE(format.output.find("dataset format 'colmap' is unknown"), std::string::npos);
}

TEST(DatasetInfo, SkipBadFramesReportsTheCount) {
  const std::string dir = RtabmapDir();
  if (dir.empty()) GTEST_SKIP() << "shared RTAB-Map fixtures not found; skipping";
  const std::filesystem::path tmp = duskmap::testing::ProcessTempDir("cli_skip");
  const std::string db = (tmp / "s.db").string();
  std::filesystem::copy_file(dir + "/rtabmap-db/session_small.db", db);
  std::filesystem::permissions(db, std::filesystem::perms::owner_write,
                               std::filesystem::perm_options::add);
  sqlite3* handle = nullptr;
  ASSERT_EQ(sqlite3_open(db.c_str(), &handle), SQLITE_OK);
  ASSERT_EQ(sqlite3_exec(handle, "UPDATE Data SET image = substr(image, 1, 300) WHERE id = 4",
                         nullptr, nullptr, nullptr),
            SQLITE_OK);
  sqlite3_close(handle);
  const Result strict = RunDuskmap("dataset info " + db);
  EXPECT_EQ(strict.exit_code, 1);
  // The header lines come first; the error is the last line.
  const std::string error_line =
      "duskmap: error: " + db + ": node 4: image: JPEG is truncated (no end-of-image marker)\n";
  ASSERT_GE(strict.output.size(), error_line.size());
  EXPECT_EQ(strict.output.substr(strict.output.size() - error_line.size()), error_line)
      << strict.output;
  const Result skipping = RunDuskmap("dataset info " + db + " --skip-bad-frames");
  ASSERT_EQ(skipping.exit_code, 0) << skipping.output;
  EXPECT_NE(skipping.output.find("frames:       9 (listed 10)"), std::string::npos) << skipping.output;
  EXPECT_NE(skipping.output.find("skipped bad frames 1"), std::string::npos);
}

}  // namespace
