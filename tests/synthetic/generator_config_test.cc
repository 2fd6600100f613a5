#include "slam/synthetic/generator_config.h"

#include <unistd.h>

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "slam/core/check.h"

namespace duskmap {
namespace {

std::string WriteConfig(const std::string& name, const std::string& text) {
  const std::string path = (std::filesystem::temp_directory_path() /
                            ("duskmap_cfg_" + name + "_" + std::to_string(::getpid()) + ".json")).string();
  std::ofstream(path) << text;
  return path;
}

std::string ErrorOf(const std::string& path) {
  try {
    ReadGeneratorConfig(path);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(ReadGeneratorConfig, DefaultConfigFileIsValidAndMatchesThePaper) {
  const GeneratorConfig config = ReadGeneratorConfig(std::string(DUSKMAP_SOURCE_DIR) + "/configs/sunset_apartment.json");
  ASSERT_EQ(config.sessions.size(), 12u);
  EXPECT_EQ(config.sessions[0].clock_time, "16:46");
  EXPECT_EQ(config.sessions[11].clock_time, "19:42");
  EXPECT_EQ(config.camera.width, 640);
  EXPECT_EQ(config.scene.living_lamp_on_from, "17:54");
  EXPECT_EQ(config.scene.bedroom_ceiling_cd, 0.0);  // the optional ceiling lights are off
  EXPECT_EQ(config.scene.living_ceiling_cd, 0.0);
}

TEST(ReadGeneratorConfig, ReadsTheOptionalCeilingLights) {
  const GeneratorConfig config = ReadGeneratorConfig(
      WriteConfig("ceiling", R"({"scene": {"bedroom_ceiling_cd": 70, "living_ceiling_cd": 80}})"));
  EXPECT_EQ(config.scene.bedroom_ceiling_cd, 70.0);
  EXPECT_EQ(config.scene.living_ceiling_cd, 80.0);
}

TEST(ReadGeneratorConfig, UnknownKeyIsNamed) {
  const std::string error = ErrorOf(WriteConfig("unknown", R"({"camera": {"widht": 320}})"));
  EXPECT_NE(error.find("widht"), std::string::npos) << error;
  EXPECT_NE(error.find("camera"), std::string::npos) << error;
}

TEST(ReadGeneratorConfig, MalformedJsonNamesTheFile) {
  const std::string path = WriteConfig("malformed", R"({"seed": 3,)");
  const std::string error = ErrorOf(path);
  EXPECT_NE(error.find(path), std::string::npos) << error;
  EXPECT_EQ(error.find('\n'), std::string::npos);
}

TEST(ReadGeneratorConfig, InconsistentValuesAreRejected) {
  EXPECT_NE(ErrorOf(WriteConfig("type", R"({"camera": {"width": "wide"}})")).find("width"), std::string::npos);
  EXPECT_NE(ErrorOf(WriteConfig("range", R"({"route": {"lateral_max_m": 2.0}})")).find("route.lateral_max_m"), std::string::npos);
  EXPECT_NE(ErrorOf(WriteConfig("dup", R"({"sessions": [{"name": "1", "clock_time": "16:46"}, {"name": "1", "clock_time": "17:00"}]})")).find("duplicate"), std::string::npos);
  EXPECT_NE(ErrorOf(WriteConfig("time", R"({"sessions": [{"name": "1", "clock_time": "4pm"}]})")).find("4pm"), std::string::npos);
  EXPECT_NE(ErrorOf(WriteConfig("depth", R"({"depth": {"max_range_m": 0.1}})")).find("depth.min_range_m"), std::string::npos);
}

TEST(ReadGeneratorConfig, MissingFileNamesIt) {
  EXPECT_NE(ErrorOf("/nonexistent/duskmap.json").find("/nonexistent/duskmap.json"), std::string::npos);
}

}  // namespace
}  // namespace duskmap
