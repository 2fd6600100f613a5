#include "slam/features/surf.h"

#include <cmath>

#include <gtest/gtest.h>

#include "slam/features/eval/homography_metrics.h"
#include "tests/features/test_images.h"

namespace duskmap {
namespace {

using testing::TexturedImage;
using testing::WarpRotateScale;

FrameFeatures ExtractSurf(const cv::Mat& image, SurfOptions options = {}) {
  return SurfExtractor(options, 1000).Extract(image);
}

PairMetrics Compare(const cv::Mat& ref, const cv::Mat& tgt, const cv::Matx33d& h,
                    SurfOptions options = {}) {
  return EvaluatePair(ExtractSurf(ref, options), ref.size(), ExtractSurf(tgt, options), tgt.size(),
                      h, HomographyMetricsOptions());
}

TEST(SurfTest, DescriptorLayoutIsUnitNormalised64Or128) {
  const cv::Mat image = TexturedImage();
  for (bool extended : {false, true}) {
    SurfOptions options;
    options.extended = extended;
    const FrameFeatures f = ExtractSurf(image, options);
    ASSERT_GT(f.size(), 300u);
    EXPECT_LE(f.size(), 1000u);
    EXPECT_EQ(f.descriptors.cols, extended ? 128 : 64);
    EXPECT_EQ(f.descriptors.type(), CV_32F);
    EXPECT_EQ(f.DescriptorBytes(), extended ? 512u : 256u);
    for (int r = 0; r < f.descriptors.rows; ++r) {
      EXPECT_NEAR(cv::norm(f.descriptors.row(r)), 1.0, 1e-4);
    }
    // |dx| and |dy| sums are non-negative in the 64-D layout.
    if (!extended) {
      for (int r = 0; r < f.descriptors.rows; ++r) {
        for (int s = 0; s < 16; ++s) {
          EXPECT_GE(f.descriptors.at<float>(r, 4 * s + 1), 0.0f);
          EXPECT_GE(f.descriptors.at<float>(r, 4 * s + 3), 0.0f);
        }
      }
    }
    for (size_t i = 1; i < f.size(); ++i) {
      EXPECT_GE(f.keypoints[i - 1].response, f.keypoints[i].response);
    }
  }
}

TEST(SurfTest, DetectsABlobAtItsScale) {
  // A dark disc of radius r on white: the Hessian peaks at its centre at a
  // scale s ~ r / sqrt(2), i.e. filter size ~ 9 r / (1.2 sqrt(2)).
  cv::Mat image(200, 200, CV_8UC1, cv::Scalar(230));
  cv::circle(image, cv::Point(100, 100), 12, cv::Scalar(20), cv::FILLED, cv::LINE_AA);
  const FrameFeatures f = ExtractSurf(image);
  ASSERT_FALSE(f.empty());
  EXPECT_NEAR(f.keypoints[0].pt.x, 100.0, 1.5);
  EXPECT_NEAR(f.keypoints[0].pt.y, 100.0, 1.5);
  const double expected_size = 9.0 * 12.0 / (1.2 * std::sqrt(2.0));
  EXPECT_NEAR(f.keypoints[0].size, expected_size, 0.35 * expected_size);
}

TEST(SurfTest, OctavesDoubleTheFilterSizesAndSizesAreWholePixels) {
  // OpenCV's scale space: octave o holds filters (9 + 6 l) 2^o, l = 0..3
  // (Bay et al.'s paper has 15, 27, 39, 51 in octave 1), so a keypoint found
  // in octave o, interpolated at most one layer from a middle layer, has a
  // size in [9, 27] 2^o.
  EXPECT_EQ(SurfFilterSide(0, 0), 9);
  EXPECT_EQ(SurfFilterSide(0, 3), 27);
  EXPECT_EQ(SurfFilterSide(1, 0), 18);
  EXPECT_EQ(SurfFilterSide(1, 3), 54);
  EXPECT_EQ(SurfFilterSide(3, 2), 168);
  const FrameFeatures f = ExtractSurf(TexturedImage());
  ASSERT_GT(f.size(), 300u);
  int octave_one = 0;
  for (const cv::KeyPoint& kp : f.keypoints) {
    ASSERT_GE(kp.octave, 0);
    ASSERT_LT(kp.octave, 4);
    EXPECT_EQ(kp.size, std::round(kp.size));
    EXPECT_GE(kp.size, 9 << kp.octave) << kp.octave;
    EXPECT_LE(kp.size, 27 << kp.octave) << kp.octave;
    octave_one += kp.octave == 1;
  }
  EXPECT_GT(octave_one, 20);
}

TEST(SurfTest, LocatesABlobInEveryOctaveToASubpixel) {
  // Octaves sampled every 2 or 4 pixels place their samples at the centres of
  // even-sided filters (i step + (step - 1) / 2); a symmetric blob is found
  // where it is, whichever octave finds it.
  for (const double radius : {3.0, 12.0, 24.0, 40.0}) {
    cv::Mat image(300, 300, CV_8UC1, cv::Scalar(220));
    cv::circle(image, cv::Point(150 * 16, 148 * 16), static_cast<int>(radius * 16),
               cv::Scalar(30), cv::FILLED, cv::LINE_AA, 4);
    const FrameFeatures f = ExtractSurf(image);
    ASSERT_FALSE(f.empty());
    EXPECT_NEAR(f.keypoints[0].pt.x, 150.0, 0.5) << radius << " octave " << f.keypoints[0].octave;
    EXPECT_NEAR(f.keypoints[0].pt.y, 148.0, 0.5) << radius << " octave " << f.keypoints[0].octave;
  }
}

TEST(SurfTest, IsDeterministic) {
  const cv::Mat image = TexturedImage();
  const FrameFeatures a = ExtractSurf(image), b = ExtractSurf(image);
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(cv::norm(a.descriptors, b.descriptors, cv::NORM_INF), 0.0);
  for (size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a.keypoints[i].pt, b.keypoints[i].pt);
}

TEST(SurfTest, RotationInvariantButUprightIsNot) {
  const cv::Mat ref = TexturedImage();
  cv::Matx33d h;
  const cv::Mat rotated = WarpRotateScale(ref, 40.0, 1.0, &h);
  const PairMetrics oriented = Compare(ref, rotated, h);
  SurfOptions upright_options;
  upright_options.upright = true;
  const PairMetrics upright = Compare(ref, rotated, h, upright_options);
  EXPECT_GT(oriented.repeatability, 0.5);
  EXPECT_GT(oriented.matching_score, 0.3);
  EXPECT_TRUE(oriented.homography_correct);
  EXPECT_LT(upright.matching_score, 0.5 * oriented.matching_score);
  // Without rotation upright SURF matches at least as well as oriented SURF.
  cv::Matx33d identity_shift;
  const cv::Mat shifted = WarpRotateScale(ref, 0.0, 1.0, &identity_shift);
  EXPECT_GT(Compare(ref, shifted, identity_shift, upright_options).matching_score, 0.6);
}

TEST(SurfTest, ScaleBrightnessBlurAndNoiseInvariance) {
  const cv::Mat ref = TexturedImage();
  cv::Matx33d h;
  const cv::Mat scaled = WarpRotateScale(ref, 0.0, 1.4, &h);
  EXPECT_GT(Compare(ref, scaled, h).matching_score, 0.25);
  const cv::Matx33d identity = cv::Matx33d::eye();
  cv::Mat brighter;
  ref.convertTo(brighter, CV_8U, 0.6, 40.0);
  EXPECT_GT(Compare(ref, brighter, identity).matching_score, 0.6);
  cv::Mat blurred;
  cv::GaussianBlur(ref, blurred, cv::Size(0, 0), 1.5);
  EXPECT_GT(Compare(ref, blurred, identity).matching_score, 0.3);
  EXPECT_GT(Compare(ref, testing::AddNoise(ref, 6.0, 3), identity).matching_score, 0.4);
}

TEST(SurfTest, ThresholdControlsTheCount) {
  const cv::Mat image = TexturedImage();
  SurfOptions low, high;
  high.hessian_threshold = 5000.0;
  EXPECT_GT(ExtractSurf(image, low).size(), ExtractSurf(image, high).size());
}

}  // namespace
}  // namespace duskmap
