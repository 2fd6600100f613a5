// End-to-end: the bad input of a sharded run and its merge, each a one-line
// error that writes no report and leaves every shard's results as they were
// (issue 46): a shard index out of range, a merge over shards of different
// configs or different duskmap versions, a shard given twice, a missing
// shard (said by its index; --allow-missing still writes the partial report).
// The Slurm side (failed shards named by the merge job) is tests/slurm/.
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/testing/cli_checks.h"
#include "tests/testing/run_duskmap.h"
#include "tests/testing/temp_dir.h"

namespace {

namespace fs = std::filesystem;

using duskmap::testing::ExpectOneLineError;
using duskmap::testing::RunDuskmap;
using duskmap::testing::Snapshot;
using Result = duskmap::testing::CliResult;

class ShardCli : public ::testing::Test {
 protected:
  // Three maps, so that each of three shards owns one; shard 1 is also run
  // with another config (frame_step 2).
  static void SetUpTestSuite() {
    dir_ = duskmap::testing::ProcessTempDir("shard_cli");
    const Result generated = duskmap::testing::GenerateSmallApartment(dir_.string(), 6, {"1", "2", "A"});
    ASSERT_EQ(generated.exit_code, 0) << generated.output;
    nlohmann::json experiment = {
        {"dataset", {{"path", (dir_ / "data").string()}, {"format", "synthetic"}}},
        {"features", {"OR"}},
        {"maps", {"1", "2", "1+2"}},
        {"localization_sessions", {"A"}}};
    std::ofstream(dir_ / "experiment.json") << experiment.dump(2);
    experiment["frame_step"] = 2;
    std::ofstream(dir_ / "other.json") << experiment.dump(2);
    for (int i = 0; i < 3; ++i) {
      const Result shard = RunDuskmap(ShardRun("experiment.json", i, "shard" + std::to_string(i)));
      ASSERT_EQ(shard.exit_code, 0) << shard.output;
    }
    const Result other = RunDuskmap(ShardRun("other.json", 1, "other1"));
    ASSERT_EQ(other.exit_code, 0) << other.output;
  }
  static void TearDownTestSuite() { fs::remove_all(dir_); }

  static std::string ShardRun(const std::string& config, int index, const std::string& output) {
    return "run " + (dir_ / config).string() + " --shard " + std::to_string(index) + "/3 --output " +
           (dir_ / output).string() + " --jobs 2";
  }
  static std::string Report(const std::vector<std::string>& shards, const std::string& output,
                            const std::string& extra = "") {
    std::string args = "report " + (dir_ / "experiment.json").string() + " --no-figures --results";
    for (const std::string& shard : shards) args += " " + (dir_ / shard).string();
    return args + " --output " + (dir_ / output).string() + " " + extra;
  }
  // Every shard folder's files, to compare before and after a refused merge.
  static std::map<std::string, std::string> Shards() {
    std::map<std::string, std::string> files;
    for (const char* shard : {"shard0", "shard1", "shard2", "other1"}) {
      const auto one = Snapshot(dir_ / shard);
      files.insert(one.begin(), one.end());
    }
    return files;
  }

  static fs::path dir_;
};

fs::path ShardCli::dir_;

TEST_F(ShardCli, ShardIndexOutOfRangeIsOneLineErrorAndWritesNothing) {
  for (const char* shard : {"5/3", "3/3", "1/0", "1of3"}) {
    const Result r = RunDuskmap("run " + (dir_ / "experiment.json").string() + " --shard " + shard +
                                " --output " + (dir_ / "out_of_range").string());
    ExpectOneLineError(r, {std::string("--shard ") + shard + ": expected i/n with 0 <= i < n"});
    EXPECT_FALSE(fs::exists(dir_ / "out_of_range")) << shard;
  }
}

TEST_F(ShardCli, ShardsOfOneRunMerge) {
  const Result r = RunDuskmap(Report({"shard2", "shard0", "shard1"}, "merged"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(fs::exists(dir_ / "merged" / "cells.csv"));
}

TEST_F(ShardCli, MergeOfShardsOfAnotherConfigIsRefused) {
  const auto before = Shards();
  ExpectOneLineError(RunDuskmap(Report({"shard0", "other1", "shard2"}, "mixed_config")),
                     {(dir_ / "other1" / "run.json").string() + ": not a shard of the run in " +
                          (dir_ / "shard0" / "run.json").string(),
                      "another configuration, first at experiment.frame_step (absent earlier, now 2)"});
  EXPECT_FALSE(fs::exists(dir_ / "mixed_config"));
  EXPECT_EQ(Shards(), before);
}

// Another program: the same config run by another duskmap version (its
// run.json's record says so).
TEST_F(ShardCli, MergeOfShardsOfAnotherProgramIsRefused) {
  fs::copy(dir_ / "shard1", dir_ / "old1", fs::copy_options::recursive);
  nlohmann::json manifest = nlohmann::json::parse(std::ifstream(dir_ / "old1" / "run.json"));
  const std::string version = manifest["configuration"]["duskmap"];
  manifest["configuration"]["duskmap"] = "0.0.1";
  std::ofstream(dir_ / "old1" / "run.json") << manifest.dump(2);
  const auto before = Snapshot(dir_ / "old1");
  ExpectOneLineError(RunDuskmap(Report({"shard0", "old1", "shard2"}, "mixed_program")),
                     {(dir_ / "old1" / "run.json").string() + ": not a shard of the run in",
                      "first at duskmap (earlier \"" + version + "\", now \"0.0.1\")"});
  EXPECT_FALSE(fs::exists(dir_ / "mixed_program"));
  EXPECT_EQ(Snapshot(dir_ / "old1"), before);
}

TEST_F(ShardCli, ShardGivenTwiceIsRefused) {
  fs::copy(dir_ / "shard0", dir_ / "copy0", fs::copy_options::recursive);
  ExpectOneLineError(RunDuskmap(Report({"shard0", "shard1", "copy0"}, "twice")),
                     {(dir_ / "copy0" / "run.json").string() + ": shard 0/3 given twice (also " +
                      (dir_ / "shard0" / "run.json").string() + ")"});
  EXPECT_FALSE(fs::exists(dir_ / "twice"));
}

// A run.json whose shard is out of range (edited, or damaged) is refused
// before any folder is sized by it.
TEST_F(ShardCli, ShardOutOfRangeInRunJsonIsRefused) {
  for (const auto& [index, count] : {std::pair{0, -1}, std::pair{3, 3}, std::pair{-2, 3},
                                    std::pair{0, 2000000000}}) {
    fs::remove_all(dir_ / "bad0");
    fs::copy(dir_ / "shard0", dir_ / "bad0", fs::copy_options::recursive);
    nlohmann::json manifest = nlohmann::json::parse(std::ifstream(dir_ / "bad0" / "run.json"));
    manifest["shard"] = {{"index", index}, {"count", count}};
    std::ofstream(dir_ / "bad0" / "run.json") << manifest.dump(2);
    const std::string shard = std::to_string(index) + "/" + std::to_string(count);
    ExpectOneLineError(RunDuskmap(Report({"bad0", "shard1", "shard2"}, "bad_range")),
                       {(dir_ / "bad0" / "run.json").string() + ": shard " + shard +
                        " is out of range (malformed run manifest)"});
    EXPECT_FALSE(fs::exists(dir_ / "bad_range")) << shard;
  }
}

TEST_F(ShardCli, MissingShardIsNamedByItsIndex) {
  const auto before = Shards();
  ExpectOneLineError(RunDuskmap(Report({"shard0", "shard2"}, "missing")),
                     {"--results: shard 1 of 3 missing (the folders hold shards 0, 2 of the run in " +
                          (dir_ / "shard0" / "run.json").string() + ")",
                      "--allow-missing for a partial report"});
  EXPECT_FALSE(fs::exists(dir_ / "missing"));
  EXPECT_EQ(Shards(), before);
  // Asked for, the partial report is written (its missing jobs counted).
  const Result partial = RunDuskmap(Report({"shard0", "shard2"}, "partial", "--allow-missing"));
  EXPECT_EQ(partial.exit_code, 0) << partial.output;
  EXPECT_TRUE(fs::exists(dir_ / "partial" / "cells.csv"));
}

}  // namespace
