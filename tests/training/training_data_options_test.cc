// The training config: its "data" section read strictly, "train" and
// "_comment" ignored, anything else refused naming the file and the key.
#include "slam/training/training_data_options.h"

#include <fstream>

#include <gtest/gtest.h>

#include "slam/core/json_codec.h"
#include "slam/training/training_data_options_json.h"
#include "tests/testing/error_of.h"
#include "tests/testing/temp_dir.h"

namespace duskmap {
namespace {

using testing::ErrorOf;

std::string WriteConfig(const std::string& name, const std::string& text) {
  const std::string path = testing::ProcessTempDir("training_options") + "/" + name;
  std::ofstream(path) << text;
  return path;
}

TEST(TrainingDataOptions, ReadsDataAndIgnoresTrainAndComment) {
  const std::string path = WriteConfig(
      "good.json",
      R"({"_comment": "x", "train": {"epochs": 3, "anything": true},
          "data": {"scenes": {"scenes": 4}, "max_pairs_per_image_pair": 20, "patch": {"patch_size_px": 16}}})");
  const TrainingDataOptions options = ReadTrainingDataConfig(path);
  EXPECT_EQ(options.scenes.scenes, 4);
  EXPECT_EQ(options.max_pairs_per_image_pair, 20);
  EXPECT_EQ(options.patch.patch_size_px, 16);
  EXPECT_DOUBLE_EQ(options.max_offset_px, 2.0);
}

TEST(TrainingDataOptions, RefusesUnknownKeysAndBadValuesNamingThem) {
  std::string error = ErrorOf([] { ReadTrainingDataConfig(WriteConfig("a.json", R"({"data": {"max_pair": 3}})")); });
  EXPECT_NE(error.find("a.json:data: unknown key 'max_pair'"), std::string::npos) << error;
  error = ErrorOf([] { ReadTrainingDataConfig(WriteConfig("b.json", R"({"data": {}, "model": 1})")); });
  EXPECT_NE(error.find("b.json: unknown key 'model'"), std::string::npos) << error;
  error = ErrorOf([] { ReadTrainingDataConfig(WriteConfig("c.json", R"({"train": {}})")); });
  EXPECT_NE(error.find("c.json: missing key 'data'"), std::string::npos) << error;
  error = ErrorOf([] { ReadTrainingDataConfig(WriteConfig("d.json", R"({"data": {"validation_scenes": 10}})")); });
  EXPECT_NE(error.find("d.json:data: validation_scenes"), std::string::npos) << error;
  error = ErrorOf([] { ReadTrainingDataConfig(WriteConfig("e.json", R"({"data": {"patch": {"patch_size_px": 2}}})")); });
  EXPECT_NE(error.find("patch.patch_size_px"), std::string::npos) << error;
}

// The committed config: the defaults but for twice the scenes' frames per
// clock time (the route's first 48 frames give a quarter of its first 96's pairs).
TEST(TrainingDataOptions, TheCommittedConfigIsTheDefaultsWithMoreFrames) {
  const TrainingDataOptions options = ReadTrainingDataConfig(std::string(DUSKMAP_SOURCE_DIR) + "/configs/dusknet.json");
  TrainingDataOptions expected;
  expected.scenes.frames_per_hour = 96;
  EXPECT_EQ(ToJsonObject(options), ToJsonObject(expected));
}

}  // namespace
}  // namespace duskmap
