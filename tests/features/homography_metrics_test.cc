#include "slam/features/eval/homography_metrics.h"

#include <gtest/gtest.h>

namespace duskmap {
namespace {

FrameFeatures Grid(const cv::Point2f& shift, int n = 10) {
  FrameFeatures f;
  f.kind = DescriptorKind::kFloat;
  f.descriptors.create(n * n, 2, CV_32F);
  for (int i = 0; i < n * n; ++i) {
    const cv::Point2f p(20.0f + 30.0f * (i % n), 20.0f + 30.0f * (i / n));
    f.keypoints.emplace_back(p + shift, 5.0f);
    f.descriptors.at<float>(i, 0) = p.x;  // descriptor = position in the reference
    f.descriptors.at<float>(i, 1) = p.y;
  }
  return f;
}

TEST(HomographyMetricsTest, PerfectTranslationScoresOne) {
  const cv::Matx33d h(1, 0, 5, 0, 1, -3, 0, 0, 1);
  const FrameFeatures ref = Grid({0, 0}), tgt = Grid({5, -3});
  const PairMetrics m = EvaluatePair(ref, {400, 400}, tgt, {400, 400}, h, HomographyMetricsOptions());
  EXPECT_EQ(m.matches, 100);
  EXPECT_EQ(m.correct_matches, 100);
  EXPECT_DOUBLE_EQ(m.repeatability, 1.0);
  EXPECT_DOUBLE_EQ(m.matching_score, 1.0);
  EXPECT_DOUBLE_EQ(m.mma[0], 1.0);
  EXPECT_TRUE(m.homography_correct);
  EXPECT_LT(m.corner_error_px, 1e-3);
}

TEST(HomographyMetricsTest, OffsetKeypointsFailTightThresholds) {
  // The target keypoints sit 2 px from the true projections.
  const cv::Matx33d h = cv::Matx33d::eye();
  const FrameFeatures ref = Grid({0, 0}), tgt = Grid({2, 0});
  const PairMetrics m = EvaluatePair(ref, {400, 400}, tgt, {400, 400}, h, HomographyMetricsOptions());
  EXPECT_DOUBLE_EQ(m.mma[0], 0.0);  // 1 px
  EXPECT_DOUBLE_EQ(m.mma[1], 1.0);  // 3 px
  EXPECT_NEAR(m.corner_error_px, 2.0, 1e-3);
  EXPECT_TRUE(m.homography_correct);
  EXPECT_DOUBLE_EQ(Repeatability(ref.keypoints, {400, 400}, tgt.keypoints, {400, 400}, h, 1.0), 0.0);
}

TEST(HomographyMetricsTest, KeypointsOutsideTheOtherImageDoNotCount) {
  // Shift by 200 px: only the half of the grid that stays inside counts.
  const cv::Matx33d h(1, 0, 200, 0, 1, 0, 0, 0, 1);
  const FrameFeatures ref = Grid({0, 0}), tgt = Grid({200, 0});
  EXPECT_DOUBLE_EQ(Repeatability(ref.keypoints, {300, 300}, tgt.keypoints, {300, 300}, h, 3.0), 1.0);
}

TEST(HomographyMetricsTest, NoFeaturesGivesZeros) {
  const PairMetrics m = EvaluatePair(FrameFeatures(), {100, 100}, FrameFeatures(), {100, 100},
                                     cv::Matx33d::eye(), HomographyMetricsOptions());
  EXPECT_EQ(m.matches, 0);
  EXPECT_EQ(m.repeatability, 0.0);
  EXPECT_FALSE(m.homography_estimated);
}

}  // namespace
}  // namespace duskmap
