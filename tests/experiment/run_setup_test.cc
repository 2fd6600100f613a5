#include "slam/experiment/run_setup.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "slam/core/check.h"
#include "tests/testing/error_of.h"
#include "tests/testing/temp_dir.h"

namespace duskmap {
namespace fs = std::filesystem;
namespace {

using testing::ErrorOf;
using testing::ProcessTempDir;

TEST(RunSetup, ParsesTheShard) {
  EXPECT_EQ(ParseShard("0/1").index, 0);
  EXPECT_EQ(ParseShard("0/1").count, 1);
  EXPECT_EQ(ParseShard("2/3").index, 2);
  EXPECT_EQ(ParseShard("2/3").count, 3);
}

TEST(RunSetup, BadShardIsOneLineErrorNamingTheFlag) {
  for (const std::string text : {"3/3", "x", "1/0", "-1/2", "1/3x", "1-3"}) {
    EXPECT_EQ(ErrorOf([&] { ParseShard(text); }),
              "--shard " + text + ": expected i/n with 0 <= i < n");
  }
}

TEST(RunSetup, AShardCountBeyondTheLimitIsRefused) {
  EXPECT_EQ(ParseShard("0/" + std::to_string(kMaxShardCount)).count, kMaxShardCount);
  const std::string text = "0/" + std::to_string(kMaxShardCount + 1);
  EXPECT_EQ(ErrorOf([&] { ParseShard(text); }),
            "--shard " + text + ": at most " + std::to_string(kMaxShardCount) + " shards");
}

TEST(RunSetup, CheckNamesTheFlag) {
  RunSetupOptions options;
  EXPECT_EQ(ErrorOf([&] { options.Check(); }), "");
  options.parallel_jobs = 5000;
  EXPECT_EQ(ErrorOf([&] { options.Check(); }), "--jobs: must be in [0, 4096], got 5000");
  options.parallel_jobs = 0;
  options.resume = true;
  options.overwrite = true;
  EXPECT_EQ(ErrorOf([&] { options.Check(); }),
            "--resume and --overwrite: give one (continue the earlier run, or redo it)");
  options.overwrite = false;
  options.shard = "1/1";
  EXPECT_EQ(ErrorOf([&] { options.Check(); }), "--shard 1/1: expected i/n with 0 <= i < n");
}

TEST(RunSetup, AMissingConfigFailsBeforeTheResultsFolderIsMade) {
  const fs::path root = ProcessTempDir("run_setup_missing_config");
  RunSetupOptions options;
  options.config_path = (root / "none.json").string();
  options.output_dir = root / "out";
  bool told = false;
  const std::string error = ErrorOf(
      [&] { PrepareRun(options, [&](const std::vector<SkippedFeature>&) { told = true; }); });
  EXPECT_NE(error.find((root / "none.json").string()), std::string::npos) << error;
  EXPECT_FALSE(told);
  EXPECT_FALSE(fs::exists(root / "out"));
}

}  // namespace
}  // namespace duskmap
