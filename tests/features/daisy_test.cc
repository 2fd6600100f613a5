#include "slam/features/daisy.h"

#include <cmath>

#include <gtest/gtest.h>

#include "slam/features/homography_metrics.h"
#include "tests/features/test_images.h"

namespace duskmap {
namespace {

TEST(DaisyTest, LayoutIs200FloatsOf25UnitHistograms) {
  const DaisyOptions options;
  EXPECT_EQ(DaisyDimension(options), 200);
  const FrameFeatures f = DaisyExtractor(options, SurfOptions(), 1000).Extract(testing::TexturedImage());
  ASSERT_GT(f.size(), 300u);
  EXPECT_EQ(f.descriptors.cols, 200);
  EXPECT_EQ(f.DescriptorBytes(), 800u);
  for (int r = 0; r < f.descriptors.rows; ++r) {
    for (int hist = 0; hist < 25; ++hist) {
      const cv::Mat h = f.descriptors.row(r).colRange(hist * 8, hist * 8 + 8);
      double min_value;
      cv::minMaxLoc(h, &min_value);
      EXPECT_GE(min_value, 0.0);
      const double norm = cv::norm(h);
      EXPECT_TRUE(std::abs(norm - 1.0) < 1e-4 || norm == 0.0) << norm;
    }
  }
}

TEST(DaisyTest, HistogramsPointAlongTheGradient) {
  // Intensity rising to the right: only bins around 0 degrees respond.
  cv::Mat ramp(120, 120, CV_8UC1);
  for (int x = 0; x < 120; ++x) ramp.col(x).setTo(x * 2);
  DaisyOptions options;
  const DaisyMaps maps = ComputeDaisyMaps(ramp, options);
  const cv::Mat d = DescribeDaisy(maps, options, {cv::KeyPoint(60, 60, 10)});
  for (int hist = 0; hist < 25; ++hist) {
    const float* h = d.ptr<float>(0) + hist * 8;
    EXPECT_GT(h[0], 0.6f);                // 0 degrees
    EXPECT_NEAR(h[4], 0.0f, 1e-4);        // 180 degrees: no negative gradient
    EXPECT_NEAR(h[1], h[7], 1e-3);        // symmetric around the gradient
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
