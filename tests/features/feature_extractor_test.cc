// The common Extract() behaviour: input conversion, bad input, depth and 3D
// points, limiting.
#include "slam/features/feature_factory.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "tests/features/test_images.h"

namespace duskmap {
namespace {

std::unique_ptr<FeatureExtractor> Make(const std::string& type, int max_features = 1000) {
  FeatureOptions options;
  options.type = type;
  options.max_features = max_features;
  options.vocabulary_features = std::min(400, max_features);
  return CreateFeatureExtractor(options);
}

class BadInputTest : public ::testing::TestWithParam<std::string> {};

TEST_P(BadInputTest, EmptyFlatAndTinyImagesGiveNoFeatures) {
  const auto extractor = Make(GetParam());
  EXPECT_TRUE(extractor->Extract(cv::Mat()).empty());
  const FrameFeatures flat = extractor->Extract(cv::Mat(120, 160, CV_8UC1, cv::Scalar(77)));
  EXPECT_TRUE(flat.empty());
  EXPECT_TRUE(flat.descriptors.empty());
  for (const cv::Size size : {cv::Size(1, 1), cv::Size(5, 3), cv::Size(20, 20), cv::Size(40, 30),
                               cv::Size(63, 200), cv::Size(64, 64), cv::Size(100, 70)}) {
    const cv::Mat tiny = testing::TexturedImage(size.width, size.height, 5);
    const FrameFeatures f = extractor->Extract(tiny);
    EXPECT_EQ(f.descriptors.rows, static_cast<int>(f.size())) << size;
    for (const cv::KeyPoint& kp : f.keypoints) {
      EXPECT_TRUE(kp.pt.x >= 0 && kp.pt.y >= 0 && kp.pt.x < size.width && kp.pt.y < size.height);
    }
  }
}

TEST_P(BadInputTest, ColourAndAlphaInputEqualGray) {
  const auto extractor = Make(GetParam());
  const cv::Mat gray = testing::TexturedImage(320, 240, 9);
  cv::Mat bgr, bgra;
  cv::cvtColor(gray, bgr, cv::COLOR_GRAY2BGR);
  cv::cvtColor(gray, bgra, cv::COLOR_GRAY2BGRA);
  const FrameFeatures a = extractor->Extract(gray), b = extractor->Extract(bgr),
                      c = extractor->Extract(bgra);
  ASSERT_FALSE(a.empty());
  EXPECT_EQ(a.size(), b.size());
  EXPECT_EQ(a.size(), c.size());
  EXPECT_EQ(cv::norm(a.descriptors, c.descriptors, cv::NORM_INF), 0.0);
}

INSTANTIATE_TEST_SUITE_P(OwnAndOpenCv, BadInputTest,
                         ::testing::Values("surf", "sift", "brief", "brisk", "daisy", "orb", "akaze",
                                           "freak"),
                         [](const auto& info) { return info.param; });

TEST(FeatureExtractorTest, SixteenBitAndTwoChannelInputAreClearErrors) {
  const auto extractor = Make("surf");
  try {
    extractor->Extract(cv::Mat(48, 64, CV_16UC1, cv::Scalar(1000)));
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("8-bit"), std::string::npos);
  }
  EXPECT_THROW(extractor->Extract(cv::Mat(48, 64, CV_32FC1, cv::Scalar(0.5))), InputError);
  EXPECT_THROW(extractor->Extract(cv::Mat(48, 64, CV_8UC2, cv::Scalar(1, 2))), InputError);
}

TEST(FeatureExtractorTest, DepthOfAnotherSizeOrTypeIsAClearError) {
  const auto extractor = Make("surf");
  const cv::Mat image = testing::TexturedImage(320, 240, 2);
  PinholeCamera camera{320, 240, 300.0, 300.0, 159.5, 119.5};
  try {
    extractor->Extract(image, cv::Mat(120, 160, CV_32FC1, cv::Scalar(1.0f)), &camera);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("160x120"), std::string::npos);
  }
  EXPECT_THROW(extractor->Extract(image, cv::Mat(240, 320, CV_16UC1, cv::Scalar(1000)), &camera),
               InputError);
  EXPECT_THROW(extractor->Extract(image, cv::Mat(240, 320, CV_32FC1, cv::Scalar(1.0f)), nullptr),
               InputError);
}

TEST(FeatureExtractorTest, PointsFromDepthAndNaNWithout) {
  const auto extractor = Make("brief");
  const cv::Mat image = testing::TexturedImage(320, 240, 2);
  const PinholeCamera camera{320, 240, 300.0, 300.0, 159.5, 119.5};
  // Depth 2 m on the left half, missing (0 / NaN) on the right half.
  cv::Mat depth(240, 320, CV_32FC1, cv::Scalar(2.0f));
  depth.colRange(160, 240).setTo(0.0f);
  depth.colRange(240, 320).setTo(std::numeric_limits<float>::quiet_NaN());
  const FrameFeatures f = extractor->Extract(image, depth, &camera);
  ASSERT_GT(f.size(), 50u);
  int with_point = 0;
  for (size_t i = 0; i < f.size(); ++i) {
    const cv::Point2f& pt = f.keypoints[i].pt;
    if (std::lround(pt.x) < 160) {
      ASSERT_TRUE(f.HasPoint(i));
      EXPECT_FLOAT_EQ(f.points_in_camera[i].z(), 2.0f);
      EXPECT_NEAR(f.points_in_camera[i].x(), (pt.x - 159.5) / 300.0 * 2.0, 1e-5);
      ++with_point;
    } else {
      EXPECT_FALSE(f.HasPoint(i));
    }
  }
  EXPECT_GT(with_point, 10);
}

TEST(FeatureExtractorTest, MaxDepthDropsFarPoints) {
  FeatureOptions options;
  options.type = "brief";
  options.max_depth_m = 1.5;
  const auto extractor = CreateFeatureExtractor(options);
  const cv::Mat image = testing::TexturedImage(320, 240, 2);
  const PinholeCamera camera{320, 240, 300.0, 300.0, 159.5, 119.5};
  const FrameFeatures f =
      extractor->Extract(image, cv::Mat(240, 320, CV_32FC1, cv::Scalar(2.0f)), &camera);
  ASSERT_FALSE(f.empty());
  for (size_t i = 0; i < f.size(); ++i) EXPECT_FALSE(f.HasPoint(i));
}

TEST(FeatureExtractorTest, CapKeepsTheStrongest) {
  const cv::Mat image = testing::TexturedImage();
  const FrameFeatures all = Make("sift", 1000)->Extract(image);
  const FrameFeatures few = Make("sift", 100)->Extract(image);
  ASSERT_EQ(few.size(), 100u);
  ASSERT_GT(all.size(), 100u);
  // The 100 kept are among the strongest of the full set.
  EXPECT_GE(few.keypoints.back().response, all.keypoints[150].response);
}

TEST(FeatureExtractorTest, KeepStrongestReordersDescriptorRows) {
  std::vector<cv::KeyPoint> kps = {cv::KeyPoint(0, 0, 1, -1, 1.0f), cv::KeyPoint(1, 0, 1, -1, 3.0f),
                                   cv::KeyPoint(2, 0, 1, -1, -2.0f)};
  cv::Mat desc = (cv::Mat_<float>(3, 1) << 10, 30, 20);
  KeepStrongest(2, &kps, &desc);
  ASSERT_EQ(kps.size(), 2u);
  EXPECT_EQ(kps[0].pt.x, 1.0f);
  EXPECT_EQ(kps[1].pt.x, 2.0f);  // |response| orders
  EXPECT_EQ(desc.at<float>(0), 30.0f);
  EXPECT_EQ(desc.at<float>(1), 20.0f);
}

}  // namespace
}  // namespace duskmap
