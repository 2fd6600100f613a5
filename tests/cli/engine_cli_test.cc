// End-to-end: `duskmap map` and `duskmap localize` on a tiny generated
// dataset, and their one-line errors.
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "slam/experiment/job_results_json.h"
#include "tests/testing/temp_dir.h"
#include "tests/testing/run_duskmap.h"

namespace {

namespace fs = std::filesystem;

using Result = duskmap::testing::CliResult;
using duskmap::testing::RunDuskmap;

class EngineCli : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = duskmap::testing::ProcessTempDir("engine_cli");
    const Result generated = duskmap::testing::GenerateSmallApartment(
        dir_, 8, {"1", "A"});
    ASSERT_EQ(generated.exit_code, 0) << generated.output;
  }
  static void TearDownTestSuite() { fs::remove_all(dir_); }
  static std::string dir_;
};

std::string EngineCli::dir_;

TEST_F(EngineCli, MapThenLocalizeWritesOutputs) {
  const Result map =
      RunDuskmap("map --dataset " + dir_ + "/data --dataset-format synthetic --sessions 1 --output " +
                 dir_ + "/map.db --summary " + dir_ + "/map.json --frames " + dir_ + "/map.csv");
  ASSERT_EQ(map.exit_code, 0) << map.output;
  const auto map_summary = nlohmann::json::parse(std::ifstream(dir_ + "/map.json"));
  EXPECT_EQ(map_summary["nodes_per_session"][0], 8);
  EXPECT_GT(map_summary["memory_bytes"]["descriptors"].get<double>(), 0.0);

  // The format detected from the folder (a synthetic dataset's sessions have
  // rgb/ folders, like an image release; its manifest decides).
  const Result localize =
      RunDuskmap("localize --map " + dir_ + "/map.db --dataset " + dir_ +
                 "/data --session A --records " + dir_ +
                 "/a.jsonl --trajectory " + dir_ + "/a.tum --summary " + dir_ + "/a.json");
  ASSERT_EQ(localize.exit_code, 0) << localize.output;
  const auto summary = nlohmann::json::parse(std::ifstream(dir_ + "/a.json"));
  EXPECT_EQ(summary["num_frames"], 8);
  EXPECT_TRUE(summary["has_ground_truth"].get<bool>());
  EXPECT_EQ(summary["num_wrong"], 0);
  EXPECT_EQ(summary["matched_session_per_frame"].size(), 8u);
  // stdout has the summary without the per-frame list.
  EXPECT_NE(localize.output.find("\"num_frames\": 8"), std::string::npos) << localize.output;
  EXPECT_EQ(localize.output.find("matched_session_per_frame"), std::string::npos) << localize.output;
  EXPECT_GT(summary["memory_bytes"]["filter"].get<double>(), 0.0);
  EXPECT_GT(summary["memory_bytes"]["words_index"].get<double>(), 0.0);
  EXPECT_GT(summary["timings"]["total"]["max_ms"].get<double>(), 0.0);
  // One schema: the summary of a localize job of `duskmap run`, every key of
  // it and no other, and what only a command run has.
  nlohmann::json job = summary;
  for (const char* key : {"session", "wall_s", "peak_rss_bytes", "timings"}) {
    EXPECT_EQ(job.erase(key), 1u) << key;
  }
  EXPECT_EQ(duskmap::ToJsonObject(
                duskmap::ReadJsonOptions<duskmap::LocalizationJobSummary>(job, "a.json")),
            job);
  std::ifstream records(dir_ + "/a.jsonl");
  int lines = 0;
  for (std::string line; std::getline(records, line); ++lines) {
    EXPECT_TRUE(nlohmann::json::parse(line).contains("outcome"));
  }
  EXPECT_EQ(lines, 8);
  EXPECT_TRUE(fs::exists(dir_ + "/a.tum"));
}

TEST_F(EngineCli, BadMapFileIsOneLineError) {
  std::ofstream(dir_ + "/bad.db") << "not a map";
  const Result r = RunDuskmap("localize --map " + dir_ + "/bad.db --dataset " + dir_ +
                       "/data --format synthetic --session A");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.output.rfind("duskmap: error: ", 0), 0u) << r.output;
  EXPECT_NE(r.output.find("not a duskmap map"), std::string::npos) << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
}

// Records of a run without their timings, one JSON object per line.
std::vector<nlohmann::json> RecordsWithoutTimings(const std::string& path) {
  std::vector<nlohmann::json> out;
  std::ifstream in(path);
  for (std::string line; std::getline(in, line);) {
    nlohmann::json record = nlohmann::json::parse(line);
    record.erase("timings_ms");
    out.push_back(record);
  }
  return out;
}

std::string FileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// scripts/time_map_open.sh (issue 46, item 4): one line per run with the
// process wall and where it went, on a copy of the session that holds its
// first frame only; the map and the dataset untouched; bad input one line.
TEST_F(EngineCli, TimeMapOpenScriptTimesTheFirstFrame) {
  const std::string map = dir_ + "/open.db";
  ASSERT_EQ(RunDuskmap("map --dataset " + dir_ + "/data --sessions 1 --output " + map).exit_code, 0);
  const std::string saved = FileBytes(map);
  const std::string script = std::string(DUSKMAP_SOURCE_DIR) + "/scripts/time_map_open.sh";
  const std::string run = "DUSKMAP=" + std::string(DUSKMAP_EXE) + " bash " + script + " " + map + " ";
  const Result timed = duskmap::testing::RunShell(run + dir_ + "/data A 2");
  ASSERT_EQ(timed.exit_code, 0) << timed.output;
  EXPECT_EQ(std::count(timed.output.begin(), timed.output.end(), '\n'), 2) << timed.output;
  EXPECT_EQ(timed.output.rfind("wall_s ", 0), 0u) << timed.output;
  for (const std::string key : {"load_s ", "setup_s ", "restore_s ", "frame_ms ", "lcd "}) {
    EXPECT_NE(timed.output.find(key), std::string::npos) << key << timed.output;
  }
  EXPECT_EQ(FileBytes(map), saved) << "the script modified the map";
  const Result bad = duskmap::testing::RunShell(run + dir_ + "/data Z");
  EXPECT_EQ(bad.exit_code, 1) << bad.output;
  EXPECT_EQ(bad.output, dir_ + "/data: no session 'Z'\n");
}

TEST_F(EngineCli, SeveralSessionsOnOneLoadEqualSeparateRuns) {
  const std::string map = dir_ + "/multi.db";
  ASSERT_EQ(RunDuskmap("map --dataset " + dir_ + "/data --sessions 1 --output " + map).exit_code, 0);
  const std::string saved = FileBytes(map);
  const Result alone = RunDuskmap("localize --map " + map + " --dataset " + dir_ +
                                  "/data --session A --records " + dir_ + "/alone_A.jsonl");
  ASSERT_EQ(alone.exit_code, 0) << alone.output;
  EXPECT_EQ(alone.output.find("warning"), std::string::npos) << alone.output;
  // Session 1 first: A's records must not depend on it.
  const Result both = RunDuskmap("localize --map " + map + " --dataset " + dir_ +
                                 "/data --session 1 A --records " + dir_ +
                                 "/multi_{session}.jsonl --summary " + dir_ + "/multi_{session}.json");
  ASSERT_EQ(both.exit_code, 0) << both.output;
  EXPECT_EQ(RecordsWithoutTimings(dir_ + "/multi_A.jsonl"), RecordsWithoutTimings(dir_ + "/alone_A.jsonl"));
  EXPECT_EQ(RecordsWithoutTimings(dir_ + "/multi_1.jsonl").size(), 8u);
  const auto summary = nlohmann::json::parse(std::ifstream(dir_ + "/multi_A.json"));
  EXPECT_EQ(summary["session"], "A");
  EXPECT_TRUE(summary["index_restored"].get<bool>());
  EXPECT_EQ(summary["map_load_s"], 0.0);
  EXPECT_TRUE(summary["map_from_cache"].get<bool>());
  const auto first = nlohmann::json::parse(std::ifstream(dir_ + "/multi_1.json"));
  EXPECT_GT(first["map_load_s"].get<double>(), 0.0);  // the one load, on the first session
  EXPECT_FALSE(first["map_from_cache"].get<bool>());
  EXPECT_EQ(FileBytes(map), saved) << "localize modified the map";

  // Several sessions need {session} in every output path; a session twice is refused.
  for (const std::string& args :
       {std::string(" --session 1 A --records ") + dir_ + "/one.jsonl",
        std::string(" --session A A")}) {
    const Result bad = RunDuskmap("localize --map " + map + " --dataset " + dir_ + "/data" + args);
    EXPECT_EQ(bad.exit_code, 1) << args;
    EXPECT_EQ(bad.output.rfind("duskmap: error: ", 0), 0u) << bad.output;
    EXPECT_EQ(std::count(bad.output.begin(), bad.output.end(), '\n'), 1) << bad.output;
  }
  EXPECT_FALSE(fs::exists(dir_ + "/one.jsonl"));
}

TEST_F(EngineCli, DamagedStoredIndexIsRebuiltWithAWarningAndTheMapUntouched) {
  const std::string map = dir_ + "/damaged.db";
  ASSERT_EQ(RunDuskmap("map --dataset " + dir_ + "/data --sessions 1 --output " + map).exit_code, 0);
  const Result good = RunDuskmap("localize --map " + map + " --dataset " + dir_ +
                                 "/data --session A --records " + dir_ + "/good.jsonl");
  ASSERT_EQ(good.exit_code, 0) << good.output;
  // Overwrite the stored index with zeros of the same size (sqlite3's own
  // shell is not installed; python3 is, for the plots).
  const std::string sql = "UPDATE word_index SET state = zeroblob(length(state))";
  ASSERT_EQ(std::system(("python3 -c \"import sqlite3; c = sqlite3.connect('" + map + "'); c.execute('" +
                         sql + "'); c.commit()\"").c_str()),
            0);
  const std::string damaged = FileBytes(map);
  const Result rebuilt = RunDuskmap("localize --map " + map + " --dataset " + dir_ +
                                    "/data --session A --records " + dir_ + "/rebuilt.jsonl");
  ASSERT_EQ(rebuilt.exit_code, 0) << rebuilt.output;
  EXPECT_NE(rebuilt.output.find("duskmap localize: warning: " + map + ": vocabulary index rebuilt ("),
            std::string::npos)
      << rebuilt.output;
  EXPECT_NE(rebuilt.output.find("fails its checksum"), std::string::npos) << rebuilt.output;
  EXPECT_EQ(RecordsWithoutTimings(dir_ + "/rebuilt.jsonl"), RecordsWithoutTimings(dir_ + "/good.jsonl"));
  EXPECT_EQ(FileBytes(map), damaged) << "localize modified the map";
}

}  // namespace
