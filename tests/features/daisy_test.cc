#include "slam/features/daisy.h"

#include <cmath>

#include <gtest/gtest.h>

#include "slam/features/eval/homography_metrics.h"
#include "tests/features/test_images.h"

namespace duskmap {
namespace {

TEST(DaisyTest, LayoutIs200FloatsOf25Histograms) {
  DaisyOptions options;
  EXPECT_FALSE(options.normalize);  // the reference's default: raw histograms
  EXPECT_EQ(DaisyDimension(options), 200);
  for (bool normalize : {false, true}) {
    options.normalize = normalize;
    const FrameFeatures f =
        DaisyExtractor(options, SurfOptions(), 1000).Extract(testing::TexturedImage());
    ASSERT_GT(f.size(), 300u);
    EXPECT_EQ(f.descriptors.cols, 200);
    EXPECT_EQ(f.DescriptorBytes(), 800u);
    int unit = 0, raw = 0;
    for (int r = 0; r < f.descriptors.rows; ++r) {
      for (int hist = 0; hist < 25; ++hist) {
        const cv::Mat h = f.descriptors.row(r).colRange(hist * 8, hist * 8 + 8);
        double min_value;
        cv::minMaxLoc(h, &min_value);
        EXPECT_GE(min_value, 0.0);
        const double norm = cv::norm(h);
        (std::abs(norm - 1.0) < 1e-4 ? unit : raw) += norm > 0.0 ? 1 : 0;
      }
    }
    // Gradients of the image in 0..1 are far below unit length.
    EXPECT_EQ(normalize ? raw : unit, 0) << "normalize " << normalize;
    EXPECT_GT(normalize ? unit : raw, 0);
  }
}

TEST(DaisyTest, HistogramsAreTheGradientAlongEachOrientation) {
  // Intensity rising 2 grey levels per pixel to the right: every smoothing
  // keeps a ramp, so each histogram holds max(0, cos(o)) * 2 / 255.
  cv::Mat ramp(120, 120, CV_8UC1);
  for (int x = 0; x < 120; ++x) ramp.col(x).setTo(x * 2);
  DaisyOptions options;
  const DaisyMaps maps = ComputeDaisyMaps(ramp, options);
  const cv::Mat d = DescribeDaisy(maps, options, {cv::KeyPoint(60, 60, 10)});
  const float slope = 2.0f / 255.0f;
  for (int hist = 0; hist < 25; ++hist) {
    const float* h = d.ptr<float>(0) + hist * 8;
    EXPECT_NEAR(h[0], slope, 0.01f * slope) << hist;                          // 0 degrees
    EXPECT_NEAR(h[1], slope * std::sqrt(0.5f), 0.01f * slope) << hist;        // 45
    EXPECT_NEAR(h[2], 0.0f, 1e-6f);                                           // 90
    EXPECT_NEAR(h[4], 0.0f, 1e-6f);                                           // 180
    EXPECT_NEAR(h[1], h[7], 1e-6f);  // symmetric around the gradient
  }
}

TEST(DaisyTest, RawDescriptorsScaleWithContrastAndNormalisedOnesDoNot) {
  const cv::Mat image = testing::TexturedImage();
  cv::Mat dimmer;
  image.convertTo(dimmer, CV_8U, 0.5, 60.0);
  const std::vector<cv::KeyPoint> keypoints = {cv::KeyPoint(100, 100, 20), cv::KeyPoint(150, 90, 20)};
  for (bool normalize : {false, true}) {
    DaisyOptions options;
    options.normalize = normalize;
    const cv::Mat a = DescribeDaisy(ComputeDaisyMaps(image, options), options, keypoints);
    const cv::Mat b = DescribeDaisy(ComputeDaisyMaps(dimmer, options), options, keypoints);
    for (int r = 0; r < a.rows; ++r) {
      const double ratio = cv::norm(b.row(r)) / cv::norm(a.row(r));
      EXPECT_NEAR(ratio, normalize ? 1.0 : 0.5, 0.03) << "normalize " << normalize;
    }
  }
}

TEST(DaisyTest, PointsOffTheImageGiveZeroHistograms) {
  // A keypoint 4 px from the right edge: the ring points to its right (j = 0,
  // 1 and 7 of ring 0 at 5 px, the whole right half of the outer rings) lie
  // outside or within two pixels of the edge and stay zero; the centre and
  // the points to its left do not.
  const cv::Mat image = testing::TexturedImage();
  DaisyOptions options;
  const float x = static_cast<float>(image.cols - 5);
  const cv::Mat d = DescribeDaisy(ComputeDaisyMaps(image, options), options, {cv::KeyPoint(x, 100, 20)});
  auto hist_norm = [&](int region) { return cv::norm(d.row(0).colRange(region * 8, region * 8 + 8)); };
  EXPECT_GT(hist_norm(0), 0.0);
  for (int ring = 0; ring < 3; ++ring) {
    EXPECT_EQ(hist_norm(1 + ring * 8 + 0), 0.0) << ring;  // straight right
    EXPECT_GT(hist_norm(1 + ring * 8 + 4), 0.0) << ring;  // straight left
  }
}

TEST(DaisyTest, OrientationOptionMakesItRotationInvariant) {
  const cv::Mat ref = testing::TexturedImage();
  cv::Matx33d h;
  const cv::Mat rotated = testing::WarpRotateScale(ref, 60.0, 1.0, &h);
  auto score = [&](bool use_orientation) {
    DaisyOptions options;
    options.use_orientation = use_orientation;
    const DaisyExtractor extractor(options, SurfOptions(), 1000);
    return EvaluatePair(extractor.Extract(ref), ref.size(), extractor.Extract(rotated),
                        rotated.size(), h, HomographyMetricsOptions())
        .matching_score;
  };
  const double fixed = score(false), oriented = score(true);
  EXPECT_LT(fixed, 0.1);
  EXPECT_GT(oriented, 0.3);
}

}  // namespace
}  // namespace duskmap
