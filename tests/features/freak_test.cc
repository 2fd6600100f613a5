#include "slam/features/freak.h"

#include <bitset>
#include <set>

#include <gtest/gtest.h>

#include "slam/features/eval/homography_metrics.h"
#include "tests/features/test_images.h"

namespace duskmap {
namespace {

TEST(FreakTest, PatternHas43FieldsAnd512DistinctPairs) {
  const FreakPattern& p = GetFreakPattern();
  EXPECT_EQ(p.pairs.size(), 512u);
  EXPECT_EQ(p.orientation_pairs.size(), 45u);
  std::set<std::array<uint8_t, 2>> unique(p.pairs.begin(), p.pairs.end());
  EXPECT_EQ(unique.size(), 512u);
  for (const auto& pair : p.pairs) {
    EXPECT_LT(pair[0], 43);
    EXPECT_LT(pair[1], 43);
    EXPECT_NE(pair[0], pair[1]);
  }
  // Retina-like: fields grow with eccentricity; the outermost ring lies at 2/3.
  for (int f = 0; f + 6 < 42; ++f) {
    EXPECT_GE(p.sigmas[f], p.sigmas[f + 6]);
    EXPECT_GT(std::hypot(p.centers[f].x, p.centers[f].y),
              std::hypot(p.centers[f + 6].x, p.centers[f + 6].y));
  }
  EXPECT_NEAR(std::hypot(p.centers[0].x, p.centers[0].y), 2.0 / 3.0, 1e-6);
  // Coarse to fine: the first pairs use the largest fields.
  EXPECT_GE(std::min(p.sigmas[p.pairs.front()[0]], p.sigmas[p.pairs.front()[1]]),
            std::min(p.sigmas[p.pairs.back()[0]], p.sigmas[p.pairs.back()[1]]));
}

TEST(FreakTest, DescriptorsAre64BytesWithInformativeBits) {
  const FreakExtractor extractor(FreakOptions(), GfttOptions(), FastOptions(), 1000);
  const FrameFeatures f = extractor.Extract(testing::TexturedImage());
  ASSERT_GT(f.size(), 500u);
  EXPECT_EQ(f.DescriptorBytes(), 64u);
  size_t ones = 0;
  for (int r = 0; r < f.descriptors.rows; ++r) {
    for (int c = 0; c < 64; ++c) ones += std::bitset<8>(f.descriptors.at<uint8_t>(r, c)).count();
  }
  const double fraction = static_cast<double>(ones) / (f.descriptors.rows * 512.0);
  EXPECT_GT(fraction, 0.3);
  EXPECT_LT(fraction, 0.7);
}

TEST(FreakTest, FastDetectorVariantAndOrientationSwitch) {
  const cv::Mat ref = testing::TexturedImage();
  cv::Matx33d h;
  const cv::Mat rotated = testing::WarpRotateScale(ref, 45.0, 1.0, &h);
  auto score = [&](const FreakOptions& options) {
    const FreakExtractor extractor(options, GfttOptions(), FastOptions(), 1000);
    const FrameFeatures a = extractor.Extract(ref);
    EXPECT_GT(a.size(), 300u);
    return EvaluatePair(a, ref.size(), extractor.Extract(rotated), rotated.size(), h,
                        HomographyMetricsOptions())
        .matching_score;
  };
  FreakOptions fast;
  fast.detector = "fast";
  EXPECT_GT(score(fast), 0.25);
  FreakOptions fixed;
  fixed.orientation_normalized = false;
  EXPECT_LT(score(fixed), 0.1);
}

}  // namespace
}  // namespace duskmap
