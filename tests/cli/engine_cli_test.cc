// End-to-end: `duskmap map` and `duskmap localize` on a tiny generated
// dataset, and their one-line errors.
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace {

namespace fs = std::filesystem;

struct Result {
  int exit_code = -1;
  std::string output;  // stdout and stderr
};

Result RunDuskmap(const std::string& args) {
  Result result;
  FILE* pipe = ::popen((std::string(DUSKMAP_EXE) + " " + args + " 2>&1").c_str(), "r");
  if (!pipe) return result;
  std::array<char, 4096> buffer;
  while (size_t n = std::fread(buffer.data(), 1, buffer.size(), pipe)) result.output.append(buffer.data(), n);
  const int status = ::pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

class EngineCli : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = (fs::temp_directory_path() / ("duskmap_engine_cli_" + std::to_string(::getpid()))).string();
    fs::create_directories(dir_);
    nlohmann::json config = nlohmann::json::parse(
        std::ifstream(std::string(DUSKMAP_SOURCE_DIR) + "/configs/sunset_apartment.json"));
    config["max_frames"] = 8;
    config["sessions"] = nlohmann::json::array(
        {{{"name", "1"}, {"clock_time", "16:46"}, {"role", "mapping"}},
         {{"name", "A"}, {"clock_time", "16:51"}, {"role", "localization"}}});
    std::ofstream(dir_ + "/gen.json") << config.dump();
    const Result generated =
        RunDuskmap("generate --config " + dir_ + "/gen.json --output " + dir_ + "/data");
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
  EXPECT_EQ(summary["frames"], 8);
  EXPECT_TRUE(summary["evaluated"].get<bool>());
  EXPECT_EQ(summary["wrong"], 0);
  EXPECT_GT(summary["memory_bytes"]["filter"].get<double>(), 0.0);
  EXPECT_GT(summary["memory_bytes"]["words_index"].get<double>(), 0.0);
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

}  // namespace
