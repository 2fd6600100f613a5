// The image pairs of a training scene, and the pairs of a rendered one: each
// pair's keypoint in B, back-projected with B's exact depth, lands on A's
// surface point.
#include "slam/training/training_pairs.h"

#include <algorithm>
#include <set>
#include <tuple>

#include <opencv2/imgproc.hpp>
#include <gtest/gtest.h>

#include "slam/features/feature_factory.h"
#include "slam/synthetic/generator.h"
#include "slam/training/correspondence.h"

namespace duskmap {
namespace {

TEST(TrainingPairs, ImagePairsCoverEveryTwoTimesOnce) {
  const std::vector<ImagePair> pairs = SelectImagePairs(4, 48, 0.25, 11);
  EXPECT_EQ(pairs.size(), SelectImagePairs(4, 48, 0.25, 11).size());
  std::set<std::tuple<int, int, int, int>> images;
  int cross_time = 0, same_time = 0;
  for (const ImagePair& p : pairs) {
    ASSERT_LT(p.frame_b, 48);
    const int d = p.frame_b - p.frame_a;
    if (p.time_a == p.time_b) {
      ++same_time;
      EXPECT_TRUE(d == 1 || d == 2);
    } else {
      ++cross_time;
      EXPECT_TRUE(d == 0 ? p.time_a < p.time_b : d == 1 || d == 2) << d;
    }
    // The same two images never twice, in either order.
    const auto key = std::min(std::make_tuple(p.time_a, p.frame_a, p.time_b, p.frame_b),
                              std::make_tuple(p.time_b, p.frame_b, p.time_a, p.frame_a));
    EXPECT_TRUE(images.insert(key).second);
  }
  EXPECT_GT(cross_time, 12 * 44);  // 12 ordered pairs of times x 48 frames, less the last frames' misses
  EXPECT_GT(same_time, 4 * 48 / 8);
  EXPECT_LT(same_time, 4 * 48 / 2);
  EXPECT_NE(pairs.size(), 0u);
  const std::vector<ImagePair> other = SelectImagePairs(4, 48, 0.25, 12);
  EXPECT_FALSE(std::equal(pairs.begin(), pairs.end(), other.begin(), other.end(), [](const ImagePair& x, const ImagePair& y) {
    return std::tie(x.time_a, x.frame_a, x.time_b, x.frame_b) == std::tie(y.time_a, y.frame_a, y.time_b, y.frame_b);
  }));
}

// Training scene 0 rendered at two of its clock times, frames 0 and 1.
TEST(TrainingPairs, RenderedPairsLandOnTheSameSurfacePoint) {
  TrainingScenesOptions scenes;
  scenes.hours_per_scene = 2;
  const TrainingScene scene = MakeTrainingScene(scenes, 0);
  const Scene apartment = BuildGeneratorScene(scene.config);
  const std::vector<TimedPose> route = GeneratorSessionRoute(scene.config, 0);
  FeatureOptions features;
  features.type = "sift";
  const auto sift = CreateFeatureExtractor(features);
  ViewGeometry views[2];
  std::vector<cv::KeyPoint> keypoints[2];
  for (int t = 0; t < 2; ++t) {
    auto simulator = StartSessionSimulator(scene.config, apartment, t, route[0].world_from_camera);
    const RgbdFrame frame = simulator->Capture(route[t].world_from_camera);
    views[t] = {simulator->last_view().depth_m.clone(), frame.camera, route[t].world_from_camera};
    cv::Mat gray;
    cv::cvtColor(frame.bgr, gray, cv::COLOR_BGR2GRAY);
    keypoints[t] = sift->Extract(gray).keypoints;
  }
  const std::vector<KeypointMatch> matches =
      MatchKeypoints(keypoints[0], views[0], keypoints[1], views[1], CorrespondenceOptions());
  ASSERT_GE(matches.size(), 20u);
  std::vector<double> errors_m;
  for (const KeypointMatch& m : matches) {
    const cv::KeyPoint& b = keypoints[1][m.index_b];
    const float z = views[1].depth_m.at<float>(cvRound(b.pt.y), cvRound(b.pt.x));
    const Eigen::Vector3d in_world = views[1].world_from_camera * views[1].camera.Unproject(b.pt.x, b.pt.y, z);
    errors_m.push_back((in_world - m.point_in_world.cast<double>()).norm());
  }
  std::sort(errors_m.begin(), errors_m.end());
  // 2 px at 2-5 m is 1-2 cm; a few keypoints on a depth edge may take B's background.
  EXPECT_LT(errors_m[errors_m.size() / 2], 0.02);
  EXPECT_LT(errors_m[errors_m.size() * 9 / 10], 0.05);
}

TEST(TrainingPairs, SceneGivesPatchesAndPointsPerPair) {
  TrainingDataOptions options;
  options.scenes.hours_per_scene = 2;
  options.scenes.frames_per_hour = 3;
  options.max_pairs_per_image_pair = 10;
  const TrainingScene scene = MakeTrainingScene(options.scenes, 1);
  const ScenePairs pairs = RenderScenePairs(scene, options);
  EXPECT_EQ(pairs.scene_index, 1);
  EXPECT_EQ(pairs.frames, 6);
  EXPECT_GT(pairs.pairs, 0);
  EXPECT_LE(pairs.pairs, static_cast<int64_t>(pairs.image_pairs) * 10);
  EXPECT_EQ(pairs.patches.size(), static_cast<size_t>(pairs.pairs) * 2 * 32 * 32);
  EXPECT_EQ(pairs.points_in_world.size(), static_cast<size_t>(pairs.pairs) * 3);
  // A patch is an image, not a constant.
  const auto first = pairs.patches.begin();
  EXPECT_NE(*std::min_element(first, first + 1024), *std::max_element(first, first + 1024));
}

}  // namespace
}  // namespace duskmap
