#include "slam/synthetic/generator.h"

#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "slam/core/check.h"
#include "slam/io/synthetic_dataset.h"
#include "tests/synthetic/small_config.h"
#include "tests/testing/temp_dir.h"

namespace duskmap {
namespace {
namespace fs = std::filesystem;

using testing::ProcessTempDir;

std::string ReadBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::map<std::string, std::string> AllFiles(const fs::path& root) {
  std::map<std::string, std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(root)) {
    if (entry.is_regular_file()) files[fs::relative(entry.path(), root).string()] = ReadBytes(entry.path());
  }
  return files;
}

TEST(GenerateDataset, SameConfigGivesByteIdenticalOutputForAnyThreadCount) {
  const fs::path root = ProcessTempDir("gen_determinism");
  GeneratorConfig config = testing::SmallConfig(3);
  GenerateOptions options;
  options.output_path = (root / "a").string();
  options.preview = true;
  GenerateDataset(config, options);
  config.threads = 1;
  options.output_path = (root / "b").string();
  GenerateDataset(config, options);
  const auto a = AllFiles(root / "a"), b = AllFiles(root / "b");
  EXPECT_GT(a.size(), 20u);
  EXPECT_TRUE(a == b);
  EXPECT_TRUE(a.count("previews/sessions.png"));
  EXPECT_TRUE(a.count("1/session.json"));
  EXPECT_TRUE(a.count("F/odometry.txt"));
}

TEST(GenerateDataset, WritesAReadableTumLayoutWithGroundTruth) {
  const fs::path root = ProcessTempDir("gen_layout");
  GenerateOptions options;
  options.output_path = (root / "data").string();
  const GenerateSummary summary = GenerateDataset(testing::SmallConfig(4), options);
  ASSERT_EQ(summary.sessions.size(), 2u);
  std::unique_ptr<DatasetReader> dataset = OpenSyntheticDataset(options.output_path);
  const std::vector<SessionInfo> sessions = dataset->Sessions();
  ASSERT_EQ(sessions.size(), 2u);
  EXPECT_EQ(sessions[1].clock_time.value_or(""), "19:42");
  std::unique_ptr<SessionReader> reader = dataset->OpenSession("1");
  int frames = 0;
  while (std::optional<RgbdFrame> f = reader->Next()) {
    EXPECT_EQ(f->bgr.cols, 160);
    EXPECT_TRUE(f->world_from_camera.has_value());
    EXPECT_GT(cv::countNonZero(f->depth_m > 0.0f), 0.5 * 160 * 120);
    double max_depth = 0;
    cv::minMaxLoc(f->depth_m, nullptr, &max_depth);
    EXPECT_LE(max_depth, 4.0 + 0.1);
    if (frames == 0) {
      EXPECT_LT(f->odom_from_body.translation.norm(), 1e-9);
    }
    ++frames;
  }
  EXPECT_EQ(frames, 4);
  EXPECT_TRUE(fs::exists(options.output_path + "/1/calibration.json"));
  // The manifest records each session's largest step, as the route has it.
  const DatasetManifest manifest = ReadManifest(options.output_path);
  ASSERT_EQ(manifest.sessions.size(), 2u);
  for (size_t i = 0; i < manifest.sessions.size(); ++i) {
    const double largest_m = LargestStepM(GeneratorSessionRoute(testing::SmallConfig(4), i));
    EXPECT_GT(largest_m, 0.0);
    ASSERT_TRUE(manifest.sessions[i].largest_step_m.has_value());
    EXPECT_DOUBLE_EQ(*manifest.sessions[i].largest_step_m, largest_m);
    EXPECT_LE(largest_m, testing::SmallConfig().route.max_step_m);
    EXPECT_DOUBLE_EQ(summary.sessions[i].largest_step_m, largest_m);
  }
}

TEST(GenerateDataset, NightIsDarkerAndNoisierThanDay) {
  const fs::path root = ProcessTempDir("gen_day_night");
  GenerateOptions options;
  options.output_path = (root / "data").string();
  const GenerateSummary summary = GenerateDataset(testing::SmallConfig(2), options);
  EXPECT_NEAR(summary.sessions[0].mean_gain, 1.0, 0.5);
  EXPECT_GT(summary.sessions[1].mean_gain, 4.0 * summary.sessions[0].mean_gain);
}

TEST(GenerateDataset, ExistingDatasetNeedsOverwrite) {
  const fs::path root = ProcessTempDir("gen_exists");
  GenerateOptions options;
  options.output_path = (root / "data").string();
  fs::create_directories(options.output_path);
  std::ofstream(options.output_path + "/keep.txt") << "x";
  EXPECT_THROW(GenerateDataset(testing::SmallConfig(1), options), InputError);
  EXPECT_TRUE(fs::exists(options.output_path + "/keep.txt"));
  // --overwrite replaces only a dataset duskmap generated (its manifest).
  options.overwrite = true;
  EXPECT_THROW(GenerateDataset(testing::SmallConfig(1), options), InputError);
  EXPECT_TRUE(fs::exists(options.output_path + "/keep.txt"));
  std::ofstream(options.output_path + "/manifest.json") << R"({"format": "duskmap-synthetic"})";
  GenerateDataset(testing::SmallConfig(1), options);
  EXPECT_FALSE(fs::exists(options.output_path + "/keep.txt"));
  EXPECT_TRUE(fs::exists(options.output_path + "/manifest.json"));
}

TEST(GenerateDataset, FailureLeavesNoHalfWrittenDataset) {
  const fs::path root = ProcessTempDir("gen_failure");
  GeneratorConfig config = testing::SmallConfig(1);
  config.scene.textures_dir = (root / "no_such_folder").string();  // fails while building the scene
  GenerateOptions options;
  options.output_path = (root / "data").string();
  EXPECT_THROW(GenerateDataset(config, options), InputError);
  EXPECT_TRUE(fs::is_empty(root));
}

TEST(GenerateDataset, UserTexturesArePutOnPictures) {
  const fs::path root = ProcessTempDir("gen_textures");
  fs::create_directories(root / "tex");
  cv::Mat image(64, 64, CV_8UC3, cv::Scalar(0, 0, 255));
  cv::imwrite((root / "tex" / "red.png").string(), image);
  GeneratorConfig config = testing::SmallConfig(1);
  config.scene.textures_dir = (root / "tex").string();
  GenerateOptions options;
  options.output_path = (root / "data").string();
  EXPECT_NO_THROW(GenerateDataset(config, options));
}

}  // namespace
}  // namespace duskmap
