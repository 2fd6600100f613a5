// The OpenCV-backed extractors: the order of detection and description.
#include <gtest/gtest.h>
#include <opencv2/features2d.hpp>

#include "slam/features/feature_factory.h"
#include "slam/features/opencv_extractors.h"
#include "tests/features/test_images.h"

namespace duskmap {
namespace {

constexpr int kMaxFeatures = 300;  // fewer than KAZE finds here: the cap is exercised

cv::Ptr<cv::KAZE> PaperKaze() {
  return cv::KAZE::create(false, false, 0.001f, 4, 4, cv::KAZE::DIFF_PM_G2);
}

FrameFeatures ExtractKaze(const cv::Mat& image, bool single_pass) {
  FeatureOptions options;
  options.type = "kaze";
  options.max_features = kMaxFeatures;
  options.vocabulary_features = kMaxFeatures;
  options.kaze.single_pass = single_pass;
  return CreateFeatureExtractor(options)->Extract(image);
}

void ExpectSame(const FrameFeatures& f, const std::vector<cv::KeyPoint>& keypoints,
                const cv::Mat& descriptors) {
  ASSERT_EQ(f.keypoints.size(), keypoints.size());
  for (size_t i = 0; i < keypoints.size(); ++i) {
    EXPECT_EQ(f.keypoints[i].pt, keypoints[i].pt) << i;
    EXPECT_EQ(f.keypoints[i].angle, keypoints[i].angle) << i;
    EXPECT_EQ(f.keypoints[i].response, keypoints[i].response) << i;
  }
  EXPECT_EQ(cv::norm(f.descriptors, descriptors, cv::NORM_INF), 0.0);
}

TEST(OpenCvExtractor, KazeByDefaultDetectsLimitsThenComputesAsTheReference) {
  const cv::Mat image = testing::TexturedImage();
  std::vector<cv::KeyPoint> keypoints;
  PaperKaze()->detect(image, keypoints);
  ASSERT_GT(keypoints.size(), static_cast<size_t>(kMaxFeatures));
  cv::Mat none, descriptors;
  KeepStrongest(kMaxFeatures, &keypoints, &none);
  PaperKaze()->compute(image, keypoints, descriptors);
  ExpectSame(ExtractKaze(image, /*single_pass=*/false), keypoints, descriptors);
}

TEST(OpenCvExtractor, KazeSinglePassDescribesInTheDetectionPassThenLimits) {
  const cv::Mat image = testing::TexturedImage();
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
  PaperKaze()->detectAndCompute(image, cv::noArray(), keypoints, descriptors);
  KeepStrongest(kMaxFeatures, &keypoints, &descriptors);
  const FrameFeatures single = ExtractKaze(image, /*single_pass=*/true);
  ExpectSame(single, keypoints, descriptors);

  // The same keypoints as the two-pass order, strongest first, but OpenCV's
  // compute on given keypoints assigns other orientations to some of them.
  const FrameFeatures two_pass = ExtractKaze(image, /*single_pass=*/false);
  ASSERT_EQ(single.size(), two_pass.size());
  int other_angle = 0;
  for (size_t i = 0; i < single.size(); ++i) {
    EXPECT_EQ(single.keypoints[i].pt, two_pass.keypoints[i].pt);
    if (single.keypoints[i].angle != two_pass.keypoints[i].angle) ++other_angle;
  }
  EXPECT_GT(other_angle, 0);
}

}  // namespace
}  // namespace duskmap
