#include "slam/registration/guided_matching.h"

#include <gtest/gtest.h>

#include "tests/registration/synthetic_pair.h"

namespace duskmap {
namespace {

FrameFeatures Features(const std::vector<cv::Point2f>& pixels, const std::vector<float>& codes) {
  FrameFeatures f;
  f.kind = DescriptorKind::kFloat;
  for (size_t i = 0; i < pixels.size(); ++i) {
    f.keypoints.emplace_back(pixels[i], 1.0f);
    f.descriptors.push_back(cv::Mat(cv::Matx12f(codes[i], 0.0f)));
  }
  return f;
}

// Map points in front of an identity camera, projecting to `pixels`.
void AddPoints(const PinholeCamera& camera, FrameFeatures* map) {
  for (const cv::KeyPoint& kp : map->keypoints) {
    map->points_in_camera.push_back(camera.Unproject(kp.pt.x, kp.pt.y, 2.0).cast<float>());
  }
}

TEST(MatchInProjectionWindow, SingleCandidateAcceptedWithoutRatio) {
  const PinholeCamera camera = testing::TestCamera();
  FrameFeatures map = Features({{100, 100}, {400, 300}}, {0.0f, 1.0f});
  AddPoints(camera, &map);
  // Query: one keypoint 10 px from the first projection with a poor descriptor,
  // nothing within 40 px of the second.
  const FrameFeatures query = Features({{110, 100}, {500, 300}}, {7.0f, 1.0f});
  const auto matches = MatchInProjectionWindow({}, map, query, camera, Rigid3d());
  ASSERT_EQ(matches.size(), 1u);
  EXPECT_EQ(matches[0].queryIdx, 0);
  EXPECT_EQ(matches[0].trainIdx, 0);
}

TEST(MatchInProjectionWindow, RatioAmongCandidatesAndSingleUse) {
  const PinholeCamera camera = testing::TestCamera();
  FrameFeatures map = Features({{200, 200}, {205, 200}}, {1.0f, 1.0f});
  AddPoints(camera, &map);
  // Two candidates near both projections: descriptor 1.0 (d=0) and 3.0 (d=4).
  const FrameFeatures query = Features({{210, 200}, {195, 205}}, {1.0f, 3.0f});
  const auto matches = MatchInProjectionWindow({}, map, query, camera, Rigid3d());
  ASSERT_EQ(matches.size(), 1u);  // the second map feature would reuse query 0
  EXPECT_EQ(matches[0].queryIdx, 0);
  EXPECT_EQ(matches[0].trainIdx, 0);
  // Ambiguous candidates (equal distances) fail the ratio.
  const FrameFeatures ambiguous = Features({{210, 200}, {195, 205}}, {2.0f, 0.0f});
  EXPECT_TRUE(MatchInProjectionWindow({}, map, ambiguous, camera, Rigid3d()).empty());
}

TEST(MatchInProjectionWindow, SkipsPointsWithoutDepthOrOutsideImage) {
  const PinholeCamera camera = testing::TestCamera();
  FrameFeatures map = Features({{100, 100}, {300, 300}}, {0.0f, 1.0f});
  AddPoints(camera, &map);
  map.points_in_camera[0].setConstant(std::numeric_limits<float>::quiet_NaN());
  map.points_in_camera[1] = Eigen::Vector3f(0.0f, 0.0f, -2.0f);  // behind
  const FrameFeatures query = Features({{100, 100}, {300, 300}}, {0.0f, 1.0f});
  EXPECT_TRUE(MatchInProjectionWindow({}, map, query, camera, Rigid3d()).empty());
}

}  // namespace
}  // namespace duskmap
