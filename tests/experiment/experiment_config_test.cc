#include "slam/experiment/experiment_config.h"

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "slam/core/check.h"
#include "tests/testing/error_of.h"
#include "tests/testing/temp_dir.h"

namespace duskmap {
namespace {

std::string WriteTemp(const std::string& name, const std::string& text) {
  const std::string path = testing::ProcessTempPath(name);
  std::ofstream(path) << text;
  return path;
}

TEST(ReadExperimentOptions, ReadsThePaperMatrix) {
  const ExperimentOptions options =
      ReadExperimentOptions(std::string(DUSKMAP_SOURCE_DIR) + "/configs/paper_matrix.json");
  EXPECT_EQ(options.maps.size(), 12u);
  EXPECT_EQ(options.localization_sessions.size(), 6u);
  EXPECT_EQ(options.consecutive_pairs.size(), 10u);
  // Relative dataset paths resolve against the config's folder.
  EXPECT_EQ(options.dataset_path, std::string(DUSKMAP_SOURCE_DIR) + "/data/sunset");
}

TEST(ReadExperimentOptions, ReadsTheReleasedDataConfigWithItsClockTimes) {
  const ExperimentOptions options = ReadExperimentOptions(
      std::string(DUSKMAP_SOURCE_DIR) + "/configs/paper_matrix_released.json");
  EXPECT_EQ(options.dataset_format, "rtabmap-db");
  EXPECT_EQ(options.maps.size(), 12u);
  ASSERT_EQ(options.session_clock_times.size(), 12u);
  EXPECT_EQ(options.session_clock_times.at("1"), "16:46");
  EXPECT_EQ(options.session_clock_times.at("F"), "19:42");
}

TEST(ReadExperimentOptions, ReadsTheQuickMatrix) {
  const ExperimentOptions options =
      ReadExperimentOptions(std::string(DUSKMAP_SOURCE_DIR) + "/configs/quick_matrix.json");
  EXPECT_FALSE(options.features.empty());
  EXPECT_FALSE(options.maps.empty());
}

TEST(ReadExperimentOptions, RejectsAMalformedClockTimeNamingTheSession) {
  const std::string path = WriteTemp(
      "clock.json", R"({"dataset": {"path": "d"}, "features": ["SI"], "maps": ["1"],
                       "localization_sessions": ["A"], "session_clock_times": {"A": "25:99"}})");
  try {
    ReadExperimentOptions(path);
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("session_clock_times.A"), std::string::npos) << e.what();
  }
}

TEST(ReadExperimentOptions, RejectsUnknownKeyNamingFileAndKey) {
  const std::string path = WriteTemp(
      "unknown.json", R"({"dataset": {"path": "d"}, "features": ["SI"], "maps": ["1"],
                         "localization_sessions": ["A"], "frame_stpe": 2})");
  try {
    ReadExperimentOptions(path);
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("frame_stpe"), std::string::npos) << e.what();
  }
}

TEST(ReadExperimentOptions, RejectsUnknownFeatureAndBadMap) {
  EXPECT_THROW(ReadExperimentOptions(WriteTemp(
                   "feature.json", R"({"dataset": {"path": "d"}, "features": ["XX"],
                                       "maps": ["1"], "localization_sessions": ["A"]})")),
               ConfigError);
  EXPECT_THROW(ReadExperimentOptions(WriteTemp(
                   "map.json", R"({"dataset": {"path": "d"}, "features": ["SI"],
                                   "maps": ["1+-2"], "localization_sessions": ["A"]})")),
               ConfigError);
}


// A config with maps 1, 1+2, 1-2-3 and 1|2 and the given "scaling" value
// (none when empty).
std::string ScalingConfig(const std::string& name, const std::string& scaling) {
  return WriteTemp(name, R"({"dataset": {"path": "d"}, "features": ["SI"],
                            "maps": ["1", "1+2", "1-2-3", "1|2"],
                            "localization_sessions": ["A"])" +
                             (scaling.empty() ? std::string() : ", \"scaling\": " + scaling) + "}");
}

TEST(ReadExperimentOptions, ReadsTheScalingCurveInItsOrder) {
  const ExperimentOptions options =
      ReadExperimentOptions(ScalingConfig("scaling.json", R"({"maps": ["1", "1+2", "1-2-3"]})"));
  ASSERT_TRUE(options.scaling.has_value());
  EXPECT_EQ(options.scaling->maps, (std::vector<std::string>{"1", "1+2", "1-2-3"}));
  EXPECT_FALSE(ReadExperimentOptions(ScalingConfig("no_scaling.json", "")).scaling.has_value());
}

TEST(ReadExperimentOptions, RejectsABadScalingCurveInOneLineNamingTheKey) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {R"({"maps": ["1", "2"]})", "scaling.maps: '2' is not one of the config's maps"},
      {R"({"maps": ["1", "1+2", "1"]})", "scaling.maps: '1' listed twice"},
      {R"({"maps": ["1"]})", "scaling.maps: a curve needs at least 2 maps, got 1"},
      {R"({})", "scaling.maps: a curve needs at least 2 maps, got 0"},
      {R"({"maps": ["1", "1|2"]})", "scaling.maps: '1|2' is a closest-in-time map"},
      {R"({"maps": ["1", "1+2"], "map": ["1"]})", "scaling: unknown key 'map'"},
      {R"({"maps": "1"})", "scaling.maps: wrong type"},
      {R"(["1", "1+2"])", "scaling: expected an object"},
  };
  for (size_t i = 0; i < cases.size(); ++i) {
    const std::string path =
        ScalingConfig("bad_scaling" + std::to_string(i) + ".json", cases[i].first);
    const std::string error = testing::ErrorOf([&] { ReadExperimentOptions(path); });
    EXPECT_NE(error.find(path), std::string::npos) << cases[i].first << ": " << error;
    EXPECT_NE(error.find(cases[i].second), std::string::npos) << cases[i].first << ": " << error;
    EXPECT_EQ(error.find('\n'), std::string::npos) << error;
  }
}

}  // namespace
}  // namespace duskmap
