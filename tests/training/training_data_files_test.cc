// The training-data folder: written and read back; every incomplete or
// foreign folder refused with one line naming the file; the held-out rule.
#include "slam/training/training_data_files.h"

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "slam/core/json_reader.h"
#include "slam/synthetic/generator.h"
#include "slam/training/held_out.h"
#include "tests/testing/error_of.h"
#include "tests/testing/temp_dir.h"

namespace duskmap {
namespace {

namespace fs = std::filesystem;
using testing::ErrorOf;

TrainingDataOptions SmallOptions() {
  TrainingDataOptions options;
  options.scenes.scenes = 3;
  options.validation_scenes = 1;
  options.patch.patch_size_px = 8;
  return options;
}

// A scene that keeps the held-out rule without rendering anything.
TrainingScene HeldOutScene(int index) {
  TrainingScene scene;
  scene.index = index;
  scene.config.seed = 5000 + index;
  scene.config.scene.furniture.pieces.clear();  // the default dataset is furnished
  return scene;
}

ScenePairs FakePairs(int index, int64_t pairs, int patch_size_px) {
  ScenePairs out;
  out.scene_index = index;
  out.pairs = pairs;
  for (int64_t i = 0; i < pairs * 2 * patch_size_px * patch_size_px; ++i) {
    out.patches.push_back(static_cast<uint8_t>((i * 7 + index) % 251));
  }
  for (int64_t i = 0; i < pairs * 3; ++i) out.points_in_world.push_back(0.25f * i + index);
  return out;
}

// Writes 3 scenes of 2, 0 and 3 pairs into `path`.
TrainingDataManifest WriteSmall(const std::string& path, bool overwrite = false) {
  const TrainingDataOptions options = SmallOptions();
  TrainingDataWriter writer(path, overwrite, options);
  const int64_t counts[] = {2, 0, 3};
  for (int i = 0; i < 3; ++i) writer.Append(HeldOutScene(i), FakePairs(i, counts[i], 8));
  return writer.Finish();
}

TEST(TrainingDataFiles, RoundTrip) {
  const std::string path = testing::ProcessTempDir("training_files") + "/round_trip";
  const TrainingDataManifest written = WriteSmall(path);
  const TrainingData data = ReadTrainingData(path);
  EXPECT_EQ(data.manifest.pairs, 5);
  EXPECT_EQ(data.manifest.train_pairs, 2);
  EXPECT_EQ(data.manifest.validation_pairs, 3);
  ASSERT_EQ(data.manifest.scenes.size(), 3u);
  EXPECT_EQ(data.manifest.scenes[2].split, "validation");
  EXPECT_EQ(data.manifest.scenes[2].first_pair, 2);
  EXPECT_EQ(data.manifest.scenes[1].seed, 5001u);
  EXPECT_EQ(data.manifest.scenes[1].texture_seed, SceneTextureSeed(HeldOutScene(1).config));
  EXPECT_EQ(data.manifest.data.patch.patch_size_px, 8);
  EXPECT_EQ(data.manifest.patch.patch_size_px, 8);
  EXPECT_EQ(data.manifest.files[0].shape, (std::vector<int64_t>{5, 2, 8, 8}));
  std::vector<uint8_t> patches = FakePairs(0, 2, 8).patches;
  const std::vector<uint8_t> last = FakePairs(2, 3, 8).patches;
  patches.insert(patches.end(), last.begin(), last.end());
  EXPECT_EQ(data.patches, patches);
  EXPECT_FLOAT_EQ(data.points_in_world[6], 2.0f);  // scene 2's first value
  const nlohmann::json json = ReadJsonFile(path + "/manifest.json");
  EXPECT_EQ(json.at("format"), "duskmap-training-pairs");
  EXPECT_EQ(json.at("version"), 1);
  EXPECT_FALSE(json.at("data").contains("threads"));  // the output does not depend on it
  EXPECT_EQ(fs::file_size(path + "/points.f32"), 5u * 3 * 4);
}

TEST(TrainingDataFiles, ReplacesOnlyItsOwnFolderAndOnlyWithOverwrite) {
  const std::string dir = testing::ProcessTempDir("training_files");
  const std::string path = dir + "/own";
  WriteSmall(path);
  EXPECT_NE(ErrorOf([&] { WriteSmall(path); }).find("--overwrite"), std::string::npos);
  EXPECT_EQ(WriteSmall(path, true).pairs, 5);
  const std::string foreign = dir + "/foreign";
  fs::create_directories(foreign);
  std::ofstream(foreign + "/notes.txt") << "mine";
  EXPECT_NE(ErrorOf([&] { WriteSmall(foreign, true); }).find("not duskmap training data"), std::string::npos);
  EXPECT_TRUE(fs::exists(foreign + "/notes.txt"));
}

// A folder written, then damaged by `damage`; the reader's error.
std::string ErrorAfter(const std::string& name, const std::function<void(const std::string&)>& damage) {
  const std::string path = testing::ProcessTempDir("training_files") + "/" + name;
  WriteSmall(path);
  damage(path);
  return ErrorOf([&] { ReadTrainingData(path); });
}

void EditManifest(const std::string& path, const std::function<void(nlohmann::json*)>& edit) {
  nlohmann::json json = ReadJsonFile(path + "/manifest.json");
  edit(&json);
  std::ofstream(path + "/manifest.json") << json.dump(2);
}

TEST(TrainingDataFiles, RefusesAFolderWithoutManifest) {
  const std::string error = ErrorAfter("no_manifest", [](const std::string& p) { fs::remove(p + "/manifest.json"); });
  EXPECT_NE(error.find("manifest.json: missing"), std::string::npos) << error;
}

TEST(TrainingDataFiles, RefusesAnotherVersionOrFormat) {
  std::string error = ErrorAfter("version", [](const std::string& p) {
    EditManifest(p, [](nlohmann::json* j) { (*j)["version"] = 2; });
  });
  EXPECT_NE(error.find("manifest.json: version 2"), std::string::npos) << error;
  error = ErrorAfter("format", [](const std::string& p) {
    EditManifest(p, [](nlohmann::json* j) { (*j)["format"] = "duskmap-synthetic"; });
  });
  EXPECT_NE(error.find("manifest.json: not a training-data manifest"), std::string::npos) << error;
}

TEST(TrainingDataFiles, RefusesAMissingFile) {
  const std::string error = ErrorAfter("no_points", [](const std::string& p) { fs::remove(p + "/points.f32"); });
  EXPECT_NE(error.find("points.f32: missing"), std::string::npos) << error;
}

TEST(TrainingDataFiles, RefusesASizeMismatch) {
  std::string error = ErrorAfter("short", [](const std::string& p) { fs::resize_file(p + "/patches.u8", 100); });
  EXPECT_NE(error.find("patches.u8: 100 bytes, the manifest says 640"), std::string::npos) << error;
  // A manifest whose pairs do not give its files' sizes.
  error = ErrorAfter("pairs", [](const std::string& p) {
    EditManifest(p, [](nlohmann::json* j) { (*j)["pairs"] = 6; });
  });
  EXPECT_NE(error.find("manifest.json: files[0] is not patches.u8"), std::string::npos) << error;
  error = ErrorAfter("patch", [](const std::string& p) {
    EditManifest(p, [](nlohmann::json* j) { (*j)["patch"]["patch_size_px"] = 16; });
  });
  EXPECT_NE(error.find("manifest.json: patch differs from data.patch"), std::string::npos) << error;
  error = ErrorAfter("scene_pairs", [](const std::string& p) {
    EditManifest(p, [](nlohmann::json* j) { (*j)["scenes"][1]["pairs"] = 1; });
  });
  EXPECT_NE(error.find("manifest.json: scene 2 starts at pair 2, expected 3"), std::string::npos) << error;
}

TEST(TrainingDataFiles, RefusesASceneOfTheDefaultDataset) {
  const GeneratorConfig defaults;
  TrainingScene same_seed = HeldOutScene(0);
  same_seed.config.seed = defaults.seed;
  EXPECT_NE(ErrorOf([&] { CheckHeldOut(same_seed); }).find("training scene 0: its seed 2024 is the default dataset's"),
            std::string::npos);
  TrainingScene same_furniture = HeldOutScene(1);
  same_furniture.config.scene.furniture = defaults.scene.furniture;
  EXPECT_NE(ErrorOf([&] { CheckHeldOut(same_furniture); }).find("furniture arrangement is the default dataset's"),
            std::string::npos);
  EXPECT_EQ(ErrorOf([&] { CheckHeldOut(HeldOutScene(2)); }), "");
  // The writer refuses it and publishes nothing.
  const std::string path = testing::ProcessTempDir("training_files") + "/held_out";
  const std::string error = ErrorOf([&] {
    TrainingDataWriter writer(path, false, SmallOptions());
    writer.Append(same_seed, FakePairs(0, 1, 8));
    writer.Finish();
  });
  EXPECT_NE(error.find("default dataset's"), std::string::npos) << error;
  EXPECT_FALSE(fs::exists(path));
}

TEST(TrainingDataFiles, EveryDefaultTrainingSceneKeepsTheHeldOutRule) {
  const TrainingScenesOptions options;
  const GeneratorConfig defaults;
  for (int i = 0; i < options.scenes; ++i) {
    const TrainingScene scene = MakeTrainingScene(options, i);
    EXPECT_EQ(ErrorOf([&] { CheckHeldOut(scene); }), "") << i;
    EXPECT_NE(scene.config.seed, defaults.seed);
  }
}

}  // namespace
}  // namespace duskmap
