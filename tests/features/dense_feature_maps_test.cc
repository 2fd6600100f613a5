#include "slam/features/dense_feature_maps.h"

#include <cmath>

#include <gtest/gtest.h>

namespace duskmap {
namespace {

cv::Mat Blob(int channels, int rows, int cols, float value = 0.0f) {
  const int sizes[4] = {1, channels, rows, cols};
  return cv::Mat(4, sizes, CV_32F, cv::Scalar(value));
}

TEST(DenseFeatureMapsTest, CellScoresDepthToSpaceOrderAndSoftmax) {
  // One cell; the logit of channel k = 8 r + c is large: the heat map peaks at (r, c).
  cv::Mat semi = Blob(65, 1, 2);
  semi.ptr<float>(0, 8 * 3 + 5)[0] = 10.0f;  // cell (0,0): row 3, col 5
  semi.ptr<float>(0, 64)[1] = 10.0f;         // cell (0,1): dustbin wins
  const cv::Mat heat = DecodeCellScores(semi, 8, true);
  ASSERT_EQ(heat.size(), cv::Size(16, 8));
  cv::Point max_loc;
  double max_value;
  cv::minMaxLoc(heat.colRange(0, 8), nullptr, &max_value, nullptr, &max_loc);
  EXPECT_EQ(max_loc, cv::Point(5, 3));
  EXPECT_NEAR(max_value, std::exp(10.0) / (std::exp(10.0) + 64.0), 1e-5);
  EXPECT_NEAR(cv::sum(heat.colRange(0, 8))[0], 1.0 - 1.0 / (std::exp(10.0) + 64.0), 1e-5);
  EXPECT_LT(cv::sum(heat.colRange(8, 16))[0], 0.01);
}

TEST(DenseFeatureMapsTest, CellScoresWithoutDustbinSumToOnePerCell) {
  // Cells of 4 pixels, 16 channels, no dustbin: each cell's heat sums to 1.
  cv::Mat logits = Blob(16, 2, 1);
  logits.ptr<float>(0, 4 * 1 + 2)[1] = 3.0f;  // cell (1,0): row 1, col 2
  const cv::Mat heat = DecodeCellScores(logits, 4, false);
  ASSERT_EQ(heat.size(), cv::Size(4, 8));
  EXPECT_NEAR(cv::sum(heat.rowRange(0, 4))[0], 1.0, 1e-5);
  EXPECT_NEAR(heat.at<float>(0, 0), 1.0 / 16.0, 1e-6);  // all logits equal
  EXPECT_NEAR(cv::sum(heat.rowRange(4, 8))[0], 1.0, 1e-5);
  EXPECT_NEAR(heat.at<float>(4 + 1, 2), std::exp(3.0) / (std::exp(3.0) + 15.0), 1e-5);
}

TEST(DenseFeatureMapsTest, ScoreMapPlaneAppliesTheSigmoidWhenAsked) {
  cv::Mat map = Blob(1, 2, 3, 0.0f);
  map.ptr<float>(0, 0)[4] = 2.0f;  // row 1, col 1
  const cv::Mat raw = ScoreMapPlane(map, false);
  ASSERT_EQ(raw.size(), cv::Size(3, 2));
  EXPECT_FLOAT_EQ(raw.at<float>(1, 1), 2.0f);
  const cv::Mat squashed = ScoreMapPlane(map, true);
  EXPECT_FLOAT_EQ(squashed.at<float>(0, 0), 0.5f);
  EXPECT_NEAR(squashed.at<float>(1, 1), 1.0 / (1.0 + std::exp(-2.0)), 1e-6);
  EXPECT_FLOAT_EQ(map.ptr<float>(0, 0)[4], 2.0f);  // the blob is not changed
}

TEST(DenseFeatureMapsTest, NmsKeepsIsolatedMaxima) {
  cv::Mat scores(40, 40, CV_32F, cv::Scalar(0.0f));
  scores.at<float>(10, 10) = 0.9f;
  scores.at<float>(10, 13) = 0.5f;  // within radius 4 of a stronger peak
  scores.at<float>(30, 30) = 0.4f;  // isolated
  const cv::Mat kept = MaxPoolNms(scores, 4);
  EXPECT_FLOAT_EQ(kept.at<float>(10, 10), 0.9f);
  EXPECT_FLOAT_EQ(kept.at<float>(10, 13), 0.0f);
  EXPECT_FLOAT_EQ(kept.at<float>(30, 30), 0.4f);
  EXPECT_EQ(cv::countNonZero(kept), 2);
  EXPECT_EQ(cv::countNonZero(MaxPoolNms(scores, 0)), 3);
}

TEST(DenseFeatureMapsTest, DescriptorsAreBilinearAndUnitNorm) {
  cv::Mat desc = Blob(256, 2, 2);
  desc.ptr<float>(0, 0)[0] = 1.0f;  // cell (0,0) points along e0
  desc.ptr<float>(0, 1)[1] = 1.0f;  // cell (0,1) along e1
  // Pixel 7.5 lies halfway between the centres (3.5 and 11.5) of cells 0 and 1.
  const cv::Mat d = SampleDescriptorMap(desc, {cv::KeyPoint(7.5f, 3.5f, 8)}, 8, true);
  EXPECT_NEAR(d.at<float>(0, 0), std::sqrt(0.5), 1e-5);
  EXPECT_NEAR(d.at<float>(0, 1), std::sqrt(0.5), 1e-5);
  EXPECT_NEAR(cv::norm(d), 1.0, 1e-5);
  const cv::Mat raw = SampleDescriptorMap(desc, {cv::KeyPoint(7.5f, 3.5f, 8)}, 8, false);
  EXPECT_NEAR(raw.at<float>(0, 0), 0.5, 1e-6);
  EXPECT_NEAR(raw.at<float>(0, 1), 0.5, 1e-6);
}

TEST(DenseFeatureMapsTest, FullResolutionMapsAreSampledAtThePixel) {
  cv::Mat desc = Blob(2, 3, 4);
  for (int i = 0; i < 12; ++i) {
    desc.ptr<float>(0, 0)[i] = static_cast<float>(i);
    desc.ptr<float>(0, 1)[i] = 1.0f;
  }
  const cv::Mat d = SampleDescriptorMap(desc, {cv::KeyPoint(2.0f, 1.0f, 1), cv::KeyPoint(2.5f, 1.0f, 1)},
                                        1, false);
  EXPECT_FLOAT_EQ(d.at<float>(0, 0), 6.0f);  // row 1, col 2
  EXPECT_FLOAT_EQ(d.at<float>(1, 0), 6.5f);  // halfway to col 3
  EXPECT_FLOAT_EQ(d.at<float>(1, 1), 1.0f);
}

TEST(DenseFeatureMapsTest, NormalizeRowsLeavesZeroRows) {
  cv::Mat rows = (cv::Mat_<float>(2, 2) << 3.0f, 4.0f, 0.0f, 0.0f);
  NormalizeRows(&rows);
  EXPECT_FLOAT_EQ(rows.at<float>(0, 0), 0.6f);
  EXPECT_FLOAT_EQ(rows.at<float>(0, 1), 0.8f);
  EXPECT_FLOAT_EQ(rows.at<float>(1, 0), 0.0f);
}

}  // namespace
}  // namespace duskmap
