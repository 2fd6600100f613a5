#include "slam/synthetic/generator_config.h"

#include <unistd.h>

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "slam/core/check.h"
#include "slam/core/json_fields.h"
#include "tests/testing/temp_dir.h"

namespace duskmap {
namespace {

std::string WriteConfig(const std::string& name, const std::string& text) {
  const std::string path = testing::ProcessTempPath("cfg_" + name + ".json");
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
  // Calibration run 22 (docs/synthetic_dataset.md): the sun per texel and the
  // image processor's noise reduction, then local contrast; run 23: the sun
  // per pixel on the furniture.
  EXPECT_TRUE(config.lighting.sun_per_texel);
  EXPECT_TRUE(config.lighting.mesh_sun_per_sample);
  EXPECT_EQ(config.camera.noise_reduction, 1.5);
  EXPECT_EQ(config.camera.sharpen_sigma_px, 5.0);
  EXPECT_EQ(config.camera.sharpen_amount, 0.5);
}

TEST(ReadGeneratorConfig, ReadsTheOptionalCeilingLights) {
  const GeneratorConfig config = ReadGeneratorConfig(
      WriteConfig("ceiling", R"({"scene": {"bedroom_ceiling_cd": 70, "living_ceiling_cd": 80}})"));
  EXPECT_EQ(config.scene.bedroom_ceiling_cd, 70.0);
  EXPECT_EQ(config.scene.living_ceiling_cd, 80.0);
}

// The optional mirrors reach the scene's quads: window glass and the bare
// floors (not the rugs); out-of-range values are refused naming the key.
TEST(ReadGeneratorConfig, ReadsTheOptionalMirrorReflectances) {
  const GeneratorConfig config = ReadGeneratorConfig(WriteConfig(
      "mirrors", R"({"scene": {"window_reflectance": 0.08, "floor_reflectance": 0.04}})"));
  EXPECT_EQ(config.scene.window_reflectance, 0.08);
  EXPECT_EQ(config.scene.floor_reflectance, 0.04);
  const Scene scene = BuildApartment(config.scene);
  int windows = 0, floors = 0, rugs_or_others = 0;
  for (const Quad& q : scene.quads) {
    if (q.emission == Emission::kSky) {
      EXPECT_EQ(q.mirror_reflectance, 0.08);
      ++windows;
    } else if (q.mirror_reflectance == 0.04) {
      EXPECT_EQ(q.origin_in_world.z(), 0.0);
      ++floors;
    } else {
      EXPECT_EQ(q.mirror_reflectance, 0.0);
      ++rugs_or_others;
    }
  }
  EXPECT_GT(windows, 0);
  EXPECT_EQ(floors, 8);  // one per room and the four door thresholds
  EXPECT_GT(rugs_or_others, 0);
  for (const Quad& q : BuildApartment(ApartmentOptions()).quads) {
    EXPECT_EQ(q.mirror_reflectance, 0.0);  // off by default
  }
  const std::string error =
      ErrorOf(WriteConfig("bad_mirror", R"({"scene": {"floor_reflectance": 0.9}})"));
  EXPECT_NE(error.find("scene.floor_reflectance"), std::string::npos) << error;
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

// Every generator config shipped under configs/ (the quick profile's
// overrides are one on their own) loads.
TEST(ReadGeneratorConfig, EveryShippedGeneratorConfigLoads) {
  const std::string configs = std::string(DUSKMAP_SOURCE_DIR) + "/configs/";
  // Every piece the default (furnished) config lists is read.
  const std::string furnished = configs + "sunset_apartment.json";
  const size_t listed = ReadJsonFile(furnished)["scene"]["furniture"]["pieces"].size();
  EXPECT_GE(listed, 15u);
  EXPECT_EQ(ReadGeneratorConfig(furnished).scene.furniture.pieces.size(), listed);
  EXPECT_TRUE(ReadGeneratorConfig(configs + "sunset_apartment_boxes.json").scene.box_furniture);
  const GeneratorConfig quick = ReadGeneratorConfig(configs + "quick/dataset_overrides.json");
  EXPECT_EQ(quick.camera.width, 480);
  EXPECT_EQ(quick.route.frame_rate_hz, 0.5);
  EXPECT_EQ(quick.sessions.size(), GeneratorConfig::DefaultSessions().size());
}

TEST(ReadGeneratorConfig, ErrorsNameTheListItemAndTheDerivedSeed) {
  const std::string missing = WriteConfig(
      "session_time", R"({"sessions": [{"name": "1", "clock_time": "16:46"}, {"name": "2"}]})");
  EXPECT_EQ(ErrorOf(missing), missing + ".sessions[1]: missing key 'clock_time'");
  const std::string unknown =
      WriteConfig("session_key", R"({"sessions": [{"name": "1", "clock_time": "16:46", "rol": "mapping"}]})");
  EXPECT_EQ(ErrorOf(unknown), unknown + ".sessions[0]: unknown key 'rol'");
  const std::string seed = WriteConfig("scene_seed", R"({"scene": {"seed": 3}})");
  EXPECT_EQ(ErrorOf(seed), seed + ".scene.seed: not set here; seed sets it");
  const std::string position = WriteConfig(
      "position", R"({"scene": {"furniture": {"pieces": [{"model": "m", "room": "kitchen", "position_m": [1]}]}}})");
  EXPECT_EQ(ErrorOf(position), position + ".scene.furniture.pieces[0].position_m: expected 2 numbers, got 1");
}

TEST(ReadGeneratorConfig, MissingFileNamesIt) {
  EXPECT_NE(ErrorOf("/nonexistent/duskmap.json").find("/nonexistent/duskmap.json"), std::string::npos);
}

}  // namespace
}  // namespace duskmap
