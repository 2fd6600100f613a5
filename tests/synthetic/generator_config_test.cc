#include "slam/synthetic/generator_config.h"

#include <unistd.h>

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "slam/core/check.h"
#include "slam/core/json_fields.h"
#include "slam/synthetic/generator_config_json.h"
#include "tests/synthetic/generator_config_files.h"
#include "tests/testing/temp_dir.h"

namespace duskmap {
namespace {

using testing::GeneratorConfigError;
using testing::WriteGeneratorConfig;

TEST(ReadGeneratorConfig, DefaultConfigFileIsValidAndMatchesThePaper) {
  const GeneratorConfig config = ReadGeneratorConfig(std::string(DUSKMAP_SOURCE_DIR) + "/configs/sunset_apartment.json");
  ASSERT_EQ(config.sessions.size(), 12u);
  EXPECT_EQ(config.sessions[0].clock_time, "16:46");
  EXPECT_EQ(config.sessions[11].clock_time, "19:42");
  EXPECT_EQ(config.camera.width, 640);
  EXPECT_EQ(config.scene.lamps.living_lamp_on_from, "17:54");
  EXPECT_EQ(config.scene.lamps.bedroom_ceiling_cd, 0.0);  // the optional ceiling lights are off
  EXPECT_EQ(config.scene.lamps.living_ceiling_cd, 0.0);
  // Calibration run 22 (docs/calibration_log.md): the sun per texel and the
  // image processor's noise reduction, then local contrast; run 23: the sun
  // per pixel on the furniture.
  EXPECT_TRUE(config.lighting.sun_per_texel);
  EXPECT_TRUE(config.lighting.mesh_sun_per_sample);
  EXPECT_EQ(config.camera.image_processor.noise_reduction, 1.5);
  EXPECT_EQ(config.camera.image_processor.sharpen_sigma_px, 5.0);
  EXPECT_EQ(config.camera.image_processor.sharpen_amount, 0.5);
}

TEST(ReadGeneratorConfig, ReadsTheOptionalCeilingLights) {
  const GeneratorConfig config = ReadGeneratorConfig(
      WriteGeneratorConfig("ceiling", R"({"scene": {"lamps": {"bedroom_ceiling_cd": 70, "living_ceiling_cd": 80}}})"));
  EXPECT_EQ(config.scene.lamps.bedroom_ceiling_cd, 70.0);
  EXPECT_EQ(config.scene.lamps.living_ceiling_cd, 80.0);
}

// The optional mirrors reach the scene's quads: window glass and the bare
// floors (not the rugs); out-of-range values are refused naming the key.
TEST(ReadGeneratorConfig, ReadsTheOptionalMirrorReflectances) {
  const GeneratorConfig config = ReadGeneratorConfig(WriteGeneratorConfig(
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
      GeneratorConfigError(WriteGeneratorConfig("bad_mirror", R"({"scene": {"floor_reflectance": 0.9}})"));
  EXPECT_NE(error.find("scene.floor_reflectance"), std::string::npos) << error;
}

TEST(ReadGeneratorConfig, UnknownKeyIsNamed) {
  const std::string error = GeneratorConfigError(WriteGeneratorConfig("unknown", R"({"camera": {"widht": 320}})"));
  EXPECT_NE(error.find("widht"), std::string::npos) << error;
  EXPECT_NE(error.find("camera"), std::string::npos) << error;
}

TEST(ReadGeneratorConfig, MalformedJsonNamesTheFile) {
  const std::string path = WriteGeneratorConfig("malformed", R"({"seed": 3,)");
  const std::string error = GeneratorConfigError(path);
  EXPECT_NE(error.find(path), std::string::npos) << error;
  EXPECT_EQ(error.find('\n'), std::string::npos);
}

TEST(ReadGeneratorConfig, InconsistentValuesAreRejected) {
  EXPECT_NE(GeneratorConfigError(WriteGeneratorConfig("type", R"({"camera": {"width": "wide"}})")).find("width"), std::string::npos);
  EXPECT_NE(GeneratorConfigError(WriteGeneratorConfig("range", R"({"route": {"lateral_max_m": 2.0}})")).find("route.lateral_max_m"), std::string::npos);
  EXPECT_NE(GeneratorConfigError(WriteGeneratorConfig("dup", R"({"sessions": [{"name": "1", "clock_time": "16:46"}, {"name": "1", "clock_time": "17:00"}]})")).find("duplicate"), std::string::npos);
  EXPECT_NE(GeneratorConfigError(WriteGeneratorConfig("time", R"({"sessions": [{"name": "1", "clock_time": "4pm"}]})")).find("4pm"), std::string::npos);
  EXPECT_NE(GeneratorConfigError(WriteGeneratorConfig("depth", R"({"depth": {"max_range_m": 0.1}})")).find("depth.min_range_m"), std::string::npos);
}

// The paper's 55 cm between consecutive 1 Hz frames: a pace that could
// break it is refused at load, naming the key, before anything is rendered.
TEST(ReadGeneratorConfig, APaceThatCouldStepOverTheCapIsRefusedNamingTheKey) {
  const std::string fast = WriteGeneratorConfig("fast", R"({"route": {"speed_mps": 0.55}})");
  const std::string error = GeneratorConfigError(fast);
  EXPECT_NE(error.find("route.speed_mps 0.55"), std::string::npos) << error;
  EXPECT_NE(error.find("more than route.max_step_m 0.55"), std::string::npos) << error;
  EXPECT_EQ(error.find('\n'), std::string::npos);
  EXPECT_NE(GeneratorConfigError(WriteGeneratorConfig("slow_frames", R"({"route": {"frame_rate_hz": 0.5}})")).find("route.speed_mps"),
            std::string::npos);
  EXPECT_NE(GeneratorConfigError(WriteGeneratorConfig("cap", R"({"route": {"max_step_m": 0}})")).find("route.max_step_m"), std::string::npos);
  // A faster walk is a choice the config makes with its cap.
  EXPECT_NO_THROW(ReadGeneratorConfig(WriteGeneratorConfig("fast_cap", R"({"route": {"speed_mps": 0.55, "max_step_m": 0.7}})")));
}

// Every generator config shipped under configs/ (the quick profile's
// overrides are one on their own) loads.
TEST(ReadGeneratorConfig, EveryShippedGeneratorConfigLoads) {
  const std::string configs = std::string(DUSKMAP_SOURCE_DIR) + "/configs/";
  // The default (furnished) config has the default model's 38 pieces.
  const std::string furnished = configs + "sunset_apartment.json";
  EXPECT_EQ(ReadGeneratorConfig(furnished).scene.furniture.pieces.size(), 38u);
  const GeneratorConfig boxes = ReadGeneratorConfig(configs + "sunset_apartment_boxes.json");
  EXPECT_EQ(boxes.model, "boxes-2026-12-02");
  EXPECT_TRUE(boxes.scene.box_furniture);
  EXPECT_TRUE(boxes.scene.furniture.pieces.empty());
  const GeneratorConfig quick = ReadGeneratorConfig(configs + "quick/dataset_overrides.json");
  EXPECT_EQ(quick.camera.width, 480);
  EXPECT_EQ(quick.route.frame_rate_hz, 0.5);
  EXPECT_EQ(quick.sessions.size(), GeneratorConfig::DefaultSessions().size());
  // The lifelong apartment: 48 mapping and 6 localization sessions on 10 days
  // (tests/synthetic/session_days_test.cc has the rest).
  const GeneratorConfig lifelong = ReadGeneratorConfig(configs + "lifelong_apartment.json");
  EXPECT_EQ(lifelong.sessions.size(), 54u);
  EXPECT_EQ(lifelong.sessions.back().day, 11);
}

TEST(ReadGeneratorConfig, ErrorsNameTheListItemAndTheDerivedSeed) {
  const std::string missing = WriteGeneratorConfig(
      "session_time", R"({"sessions": [{"name": "1", "clock_time": "16:46"}, {"name": "2"}]})");
  EXPECT_EQ(GeneratorConfigError(missing), missing + ".sessions[1]: missing key 'clock_time'");
  const std::string unknown =
      WriteGeneratorConfig("session_key", R"({"sessions": [{"name": "1", "clock_time": "16:46", "rol": "mapping"}]})");
  EXPECT_EQ(GeneratorConfigError(unknown), unknown + ".sessions[0]: unknown key 'rol'");
  const std::string seed = WriteGeneratorConfig("scene_seed", R"({"scene": {"seed": 3}})");
  EXPECT_EQ(GeneratorConfigError(seed), seed + ".scene.seed: not set here; seed sets it");
  const std::string position = WriteGeneratorConfig(
      "position", R"({"scene": {"furniture": {"pieces": [{"model": "m", "room": "kitchen", "position_m": [1]}]}}})");
  EXPECT_EQ(GeneratorConfigError(position), position + ".scene.furniture.pieces[0].position_m: expected 2 numbers, got 1");
}

// The code's defaults are the default dataset: a config that sets nothing
// but max_frames reads as configs/sunset_apartment.json with that max_frames,
// and as GeneratorConfig's defaults.
TEST(ReadGeneratorConfig, AConfigWithOnlyMaxFramesIsTheCalibratedDefault) {
  const GeneratorConfig only = ReadGeneratorConfig(WriteGeneratorConfig("only_frames", R"({"max_frames": 3})"));
  GeneratorConfig shipped = ReadGeneratorConfig(std::string(DUSKMAP_SOURCE_DIR) + "/configs/sunset_apartment.json");
  shipped.max_frames = 3;
  GeneratorConfig code;
  code.max_frames = 3;
  EXPECT_EQ(ToJsonObject(only), ToJsonObject(shipped));
  EXPECT_EQ(ToJsonObject(only), ToJsonObject(code));
  EXPECT_EQ(only.model, kDefaultGeneratorModel);
  // The calibrated values (calibration runs 10-23), not the building blocks' own defaults.
  EXPECT_FALSE(only.scene.box_furniture);
  EXPECT_EQ(only.scene.furniture.pieces.size(), 38u);
  EXPECT_EQ(only.lighting.glass_transmission, 0.35);
  EXPECT_EQ(only.lighting.horizon_elevation_deg, 14.0);
  EXPECT_EQ(only.camera.image_processor.tone_contrast, 0.5);
  EXPECT_TRUE(only.route.paced_walk);
  EXPECT_EQ(only.route.max_step_m, 0.55);
  EXPECT_NE(ToJsonObject(only.lighting), ToJsonObject(LightingOptions()));
}

// Each model is selected by name, sets every value a model decides whatever
// came before (the same values from any starting model), and takes the
// config's other keys over its own.
TEST(GeneratorModels, EachModelIsSelectableAndSetsEveryValueItDecides) {
  const std::vector<std::string> names = GeneratorModelNames();
  ASSERT_EQ(names.size(), 7u);
  EXPECT_EQ(names.front(), "boxes-2026-12-02");
  EXPECT_EQ(names.back(), kDefaultGeneratorModel);
  for (const std::string& name : names) {
    const GeneratorConfig read = ReadGeneratorConfig(WriteGeneratorConfig("model", R"({"model": ")" + name + R"("})"));
    EXPECT_EQ(read.model, name);
    for (const std::string& before : names) {
      GeneratorConfig config;
      ApplyGeneratorModel(before, &config);
      ApplyGeneratorModel(name, &config);
      EXPECT_EQ(ToJsonObject(config), ToJsonObject(read)) << name << " after " << before;
    }
  }
  const auto model = [](const std::string& name) {
    GeneratorConfig config;
    ApplyGeneratorModel(name, &config);
    return config;
  };
  // What each step of the calibration log added.
  EXPECT_TRUE(model("boxes-2026-12-02").scene.box_furniture);
  EXPECT_EQ(model("boxes-2026-12-02").camera.exposure.motion_blur_scale, 1.0);
  EXPECT_EQ(model("run10-2026-12-05").scene.lamps.intensity_scale, 3.2);
  EXPECT_FALSE(model("run10-2026-12-05").lighting.window_view_obstructed);
  EXPECT_TRUE(model("run14-2026-12-06").lighting.window_view_obstructed);
  EXPECT_EQ(model("run14-2026-12-06").lighting.glass_transmission, 0.75);
  EXPECT_EQ(model("run17-2026-12-06").lighting.glass_transmission, 0.35);
  EXPECT_FALSE(model("run17-2026-12-06").lighting.sun_per_texel);
  EXPECT_TRUE(model("run22-2026-12-06").lighting.sun_per_texel);
  EXPECT_FALSE(model("run22-2026-12-06").lighting.mesh_sun_per_sample);
  EXPECT_TRUE(model("run23-2026-12-06").lighting.mesh_sun_per_sample);
  EXPECT_FALSE(model("run23-2026-12-06").route.paced_walk);
  EXPECT_EQ(model("run23-2026-12-06").route.speed_mps, 0.55);
  EXPECT_TRUE(model("run24-2026-12-07").route.paced_walk);
  EXPECT_EQ(model("run24-2026-12-07").route.max_step_m, 0.55);
  const GeneratorConfig over = ReadGeneratorConfig(
      WriteGeneratorConfig("over", R"({"model": "boxes-2026-12-02", "lighting": {"glass_transmission": 0.5}})"));
  EXPECT_TRUE(over.scene.box_furniture);
  EXPECT_EQ(over.lighting.glass_transmission, 0.5);
}

TEST(ReadGeneratorConfig, AnUnknownModelIsRefusedNamingTheKey) {
  const std::string path = WriteGeneratorConfig("bad_model", R"({"model": "run99"})");
  const std::string error = GeneratorConfigError(path);
  EXPECT_EQ(error.find(path + ".model: unknown model 'run99' (known: boxes-2026-12-02, "), 0u) << error;
  EXPECT_NE(GeneratorConfigError(WriteGeneratorConfig("model_type", R"({"model": 23})")).find(".model: wrong type"), std::string::npos);
  GeneratorConfig config;
  config.model = "run99";
  EXPECT_THROW(config.Check(), ConfigError);
}

// The camera's options nest by stage; each flat key of before is refused
// with the key that replaced it.
TEST(ReadGeneratorConfig, TheCameraNestsByStageAndAMovedKeyIsRefusedWithItsNewKey) {
  const GeneratorConfig nested = ReadGeneratorConfig(WriteGeneratorConfig("nested", R"({"camera": {
      "exposure": {"target": 0.3, "motion_blur_scale": 0.5}, "white_balance": {"strength": 0.5},
      "noise": {"read_noise": 0.004}, "image_processor": {"tone_contrast": 0.2, "sharpen_amount": 1}}})"));
  EXPECT_EQ(nested.camera.exposure.target, 0.3);
  EXPECT_EQ(nested.camera.exposure.motion_blur_scale, 0.5);
  EXPECT_EQ(nested.camera.white_balance.strength, 0.5);
  EXPECT_EQ(nested.camera.noise.read_noise, 0.004);
  EXPECT_EQ(nested.camera.image_processor.tone_contrast, 0.2);
  EXPECT_EQ(nested.camera.image_processor.sharpen_amount, 1.0);
  const std::vector<std::pair<std::string, std::string>> moved = MovedGeneratorKeys();
  EXPECT_EQ(moved.size(), 24u);
  for (const auto& [old_key, new_key] : moved) {
    const size_t dot = old_key.find('.');
    const std::string path = WriteGeneratorConfig(
        "moved", "{\"" + old_key.substr(0, dot) + "\": {\"" + old_key.substr(dot + 1) + "\": 1}}");
    EXPECT_EQ(GeneratorConfigError(path), path + "." + old_key + ": moved to " + new_key);
  }
  const std::string range = GeneratorConfigError(WriteGeneratorConfig("range", R"({"camera": {"exposure": {"speed": 2}}})"));
  EXPECT_NE(range.find("camera.exposure.speed must be in (0, 1]"), std::string::npos) << range;
}

// Every lamp knob is read from scene.lamps; the scene carries the lamps'
// colour and shade glow to the lighting.
TEST(ReadGeneratorConfig, TheLampKnobsLiveInSceneLamps) {
  const GeneratorConfig config = ReadGeneratorConfig(WriteGeneratorConfig("lamps", R"({"model": "boxes-2026-12-02",
      "scene": {"lamps": {"intensity_scale": 2, "living_lamp_on_from": "18:00", "color_temperature_k": 4000,
                          "shade_nits_per_cd": 10}}})"));
  const LampOptions& lamps = config.scene.lamps;
  EXPECT_EQ(lamps.intensity_scale, 2.0);
  EXPECT_EQ(lamps.living_lamp_on_from, "18:00");
  EXPECT_EQ(lamps.light.color_temperature_k, 4000.0);
  EXPECT_EQ(lamps.light.shade_nits_per_cd, 10.0);
  const Scene scene = BuildApartment(config.scene);
  EXPECT_EQ(scene.lamp_light.color_temperature_k, 4000.0);
  EXPECT_EQ(scene.lamp_light.shade_nits_per_cd, 10.0);
  const SessionLighting lighting = ComputeSessionLighting(config.lighting, scene, 20.0);
  EXPECT_EQ(lighting.lamp_color_bgr, ColorTemperatureToBgr(4000.0));
  const std::string error =
      GeneratorConfigError(WriteGeneratorConfig("lamp_range", R"({"scene": {"lamps": {"color_temperature_k": 100}}})"));
  EXPECT_NE(error.find("scene.lamps.color_temperature_k must be in [1000, 12000]"), std::string::npos) << error;
}

TEST(ReadGeneratorConfig, MissingFileNamesIt) {
  EXPECT_NE(GeneratorConfigError("/nonexistent/duskmap.json").find("/nonexistent/duskmap.json"), std::string::npos);
}

}  // namespace
}  // namespace duskmap
