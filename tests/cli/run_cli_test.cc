// End-to-end: `duskmap run` and `duskmap report` on a tiny generated dataset:
// the report's files, shards merged equal one unsharded run, resume redoes
// only missing jobs, an earlier run is never overwritten silently, and a
// corrupt feature cache fails its jobs with the file named.
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/testing/temp_dir.h"
#include "tests/testing/cli_checks.h"
#include "tests/testing/run_duskmap.h"

namespace {

namespace fs = std::filesystem;

using Result = duskmap::testing::CliResult;
using duskmap::testing::ReadText;
using duskmap::testing::RunDuskmap;

// Every table's CSV except the timing table (wall-clock times differ run to run).
std::map<std::string, std::string> DeterministicTables(const fs::path& report) {
  std::map<std::string, std::string> tables;
  for (const auto& entry : fs::directory_iterator(report / "tables")) {
    const std::string name = entry.path().filename().string();
    // Timings are not deterministic.
    if (name.rfind("per_frame_timings", 0) == 0 || name.rfind("timing_budget", 0) == 0) continue;
    tables[name] = ReadText(entry.path());
  }
  return tables;
}

class RunCli : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = duskmap::testing::ProcessTempDir("run_cli");
    const Result generated = duskmap::testing::GenerateSmallApartment(
        dir_.string(), 10, {"1", "2", "A"});
    ASSERT_EQ(generated.exit_code, 0) << generated.output;
    const nlohmann::json experiment = {
        {"dataset", {{"path", (dir_ / "data").string()}, {"format", "synthetic"}}},
        {"features", {"OR", "BF", "SP"}},
        {"maps", {"1", "2", "1+2", "1-2", "1|2"}},
        {"localization_sessions", {"A"}},
        {"consecutive",
         {{"pairs", nlohmann::json::array({nlohmann::json::array({"1", "2"})})}}}};
    std::ofstream(dir_ / "experiment.json") << experiment.dump(2);
  }
  static void TearDownTestSuite() { fs::remove_all(dir_); }

  static std::string Run(const std::string& output, const std::string& extra = "") {
    return "run " + (dir_ / "experiment.json").string() + " --output " + (dir_ / output).string() +
           " --jobs 2 --no-figures " + extra;
  }

  static fs::path dir_;
};

fs::path RunCli::dir_;

TEST_F(RunCli, RunWritesJobResultsAndReport) {
  const Result r = RunDuskmap(Run("full"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  // SuperPoint has no model in this config: skipped with a notice, not a failure.
  EXPECT_NE(r.output.find("note: feature SP skipped"), std::string::npos) << r.output;
  const fs::path jobs = dir_ / "full" / "jobs";
  for (const char* job : {"extract/orb/1", "extract/brief/A", "map/OR/1+2", "map/BF/1-2",
                          "localize/OR/1+2/A", "localize/BF/2/A", "localize/OR/1/2"}) {
    EXPECT_TRUE(fs::exists(jobs / job / "summary.json")) << job;
  }
  EXPECT_TRUE(fs::exists(jobs / "map/OR/1+2/map.db"));
  EXPECT_TRUE(fs::exists(jobs / "map/OR/1+2/graph.csv"));
  EXPECT_TRUE(fs::exists(jobs / "localize/OR/1+2/A/frames.jsonl"));
  EXPECT_FALSE(fs::exists(jobs / "extract/superpoint"));

  const auto localize = nlohmann::json::parse(std::ifstream(jobs / "localize/OR/1/A/summary.json"));
  EXPECT_EQ(localize["num_frames"], 10);
  EXPECT_TRUE(localize["has_ground_truth"].get<bool>());
  EXPECT_GT(localize["mean_times_ms"]["features"].get<double>(), 0.0)
      << "the extraction time of the cached features is reported";
  const auto map = nlohmann::json::parse(std::ifstream(jobs / "map/OR/1+2/summary.json"));
  EXPECT_EQ(map["num_nodes"], 20);
  EXPECT_EQ(map["descriptor_bytes_per_feature"], 32);

  const fs::path report = dir_ / "full" / "report";
  for (const char* file : {"tables.md", "tables.tex", "cells.csv", "timeline.csv", "consecutive.csv"}) {
    EXPECT_TRUE(fs::exists(report / file)) << file;
  }
  const std::string tables = ReadText(report / "tables.md");
  EXPECT_NE(tables.find("| 1\\|2 |"), std::string::npos) << tables;
  EXPECT_NE(tables.find("| map | OR | BF |"), std::string::npos) << tables;
  const nlohmann::json manifest = nlohmann::json::parse(std::ifstream(dir_ / "full" / "run.json"));
  EXPECT_EQ(manifest["features"], nlohmann::json({"OR", "BF"}));
  EXPECT_EQ(manifest["session_clock_min"]["2"], 17 * 60 + 27);
}

TEST_F(RunCli, ShardsMergedEqualOneRun) {
  ASSERT_EQ(RunDuskmap(Run("whole")).exit_code, 0);
  for (int i = 0; i < 2; ++i) {
    const Result shard = RunDuskmap(Run("shard" + std::to_string(i), "--shard " +
                                                                          std::to_string(i) + "/2"));
    ASSERT_EQ(shard.exit_code, 0) << shard.output;
    EXPECT_FALSE(fs::exists(dir_ / ("shard" + std::to_string(i)) / "report"))
        << "a shard alone writes no report";
  }
  const Result partial = RunDuskmap("report " + (dir_ / "experiment.json").string() +
                                    " --results " + (dir_ / "shard0").string() + " --output " +
                                    (dir_ / "partial").string() + " --no-figures");
  EXPECT_EQ(partial.exit_code, 1) << "one shard alone misses jobs: " << partial.output;
  const Result merged = RunDuskmap("report " + (dir_ / "experiment.json").string() +
                                   " --results " + (dir_ / "shard0").string() + " " +
                                   (dir_ / "shard1").string() + " --output " +
                                   (dir_ / "merged").string() + " --no-figures");
  ASSERT_EQ(merged.exit_code, 0) << merged.output;
  const auto whole = DeterministicTables(dir_ / "whole" / "report");
  EXPECT_GE(whole.size(), 8u);
  EXPECT_EQ(DeterministicTables(dir_ / "merged"), whole);
  EXPECT_EQ(ReadText(dir_ / "merged" / "cells.csv"), ReadText(dir_ / "whole" / "report" / "cells.csv"));
  EXPECT_EQ(ReadText(dir_ / "merged" / "timeline.csv"),
            ReadText(dir_ / "whole" / "report" / "timeline.csv"));
}

TEST_F(RunCli, ResumeRedoesOnlyMissingJobsAndEarlierRunsAreKept) {
  ASSERT_EQ(RunDuskmap(Run("resume")).exit_code, 0);
  const fs::path cells = dir_ / "resume" / "report" / "cells.csv";
  const std::string before = ReadText(cells);

  const Result again = RunDuskmap(Run("resume"));
  EXPECT_EQ(again.exit_code, 1);
  EXPECT_NE(again.output.find("holds an earlier run; pass --resume"), std::string::npos)
      << again.output;

  // An interrupted run: one localization job missing, one left half-written.
  fs::remove_all(dir_ / "resume" / "jobs" / "localize/OR/1+2/A");
  fs::rename(dir_ / "resume" / "jobs" / "localize/BF/1/A",
             dir_ / "resume" / "jobs" / "localize/BF/1/A.partial");
  const Result resumed = RunDuskmap(Run("resume", "--resume"));
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_NE(resumed.output.find(": 2 jobs run,"), std::string::npos) << resumed.output;
  EXPECT_FALSE(fs::exists(dir_ / "resume" / "jobs" / "localize/BF/1/A.partial"));
  EXPECT_EQ(ReadText(cells), before) << "deterministic: the redone jobs give the same results";
}

// Features kept across runs (--feature-cache): a second run into another
// folder restores every extract job instead of extracting, with the first
// run's extraction timings, and gives the first run's cells.
TEST_F(RunCli, FeatureCacheSharedAcrossRunsGivesTheSameCells) {
  const std::string cache = (dir_ / "shared_features").string();
  const Result first = RunDuskmap(Run("cached1", "--feature-cache " + cache));
  ASSERT_EQ(first.exit_code, 0) << first.output;
  const Result second = RunDuskmap(Run("cached2", "--feature-cache " + cache));
  ASSERT_EQ(second.exit_code, 0) << second.output;
  auto summary = [&](const std::string& run, const std::string& job) {
    return nlohmann::json::parse(std::ifstream(dir_ / run / "jobs" / job / "summary.json"));
  };
  for (const char* job : {"extract/orb/1", "extract/orb/2", "extract/orb/A", "extract/brief/1",
                          "extract/brief/2", "extract/brief/A"}) {
    const nlohmann::json stored = summary("cached1", job), restored = summary("cached2", job);
    EXPECT_EQ(stored["shared_cache"].get<std::string>().rfind("stored ", 0), 0u) << job;
    EXPECT_EQ(restored["shared_cache"].get<std::string>().rfind("restored ", 0), 0u) << job;
    EXPECT_EQ(restored["extraction_ms"], stored["extraction_ms"]) << job;
    EXPECT_EQ(ReadText(dir_ / "cached2" / "jobs" / job / "features.bin"),
              ReadText(dir_ / "cached1" / "jobs" / job / "features.bin"))
        << job;
  }
  EXPECT_EQ(ReadText(dir_ / "cached2" / "report" / "cells.csv"),
            ReadText(dir_ / "cached1" / "report" / "cells.csv"));
  // Inside the results folder, an --overwrite would remove it: refused before anything is written.
  const Result inside = RunDuskmap(Run("cached3", "--feature-cache " + (dir_ / "cached3" / "features").string()));
  EXPECT_EQ(inside.exit_code, 1) << inside.output;
  EXPECT_NE(inside.output.find("must lie outside --output"), std::string::npos) << inside.output;
  EXPECT_FALSE(fs::exists(dir_ / "cached3"));
}

TEST_F(RunCli, CorruptFeatureCacheFailsItsJobsNamingTheFile) {
  ASSERT_EQ(RunDuskmap(Run("corrupt")).exit_code, 0);
  const fs::path cache = dir_ / "corrupt" / "jobs" / "extract/orb/A" / "features.bin";
  const auto size = fs::file_size(cache);
  fs::resize_file(cache, size / 2);
  fs::remove_all(dir_ / "corrupt" / "jobs" / "localize/OR/1/A");
  const Result r = RunDuskmap(Run("corrupt", "--resume"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.output.find("failed: localize/OR/1/A: " + cache.string() + ": truncated feature cache"),
            std::string::npos)
      << r.output;
  EXPECT_TRUE(fs::exists(dir_ / "corrupt" / "jobs" / "localize/OR/2/A" / "summary.json"))
      << "finished jobs are kept";
}

TEST_F(RunCli, BadConfigIsOneLineError) {
  std::ofstream(dir_ / "bad.json") << R"({"dataset": {"path": "nowhere"}, "features": ["XX"]})";
  const Result r = RunDuskmap("run " + (dir_ / "bad.json").string() + " --output " +
                              (dir_ / "bad").string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.output.rfind("duskmap: error: ", 0), 0u) << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  EXPECT_FALSE(fs::exists(dir_ / "bad"));
}

}  // namespace
