#include "slam/features/brief.h"

#include <bitset>
#include <set>

#include <gtest/gtest.h>

#include "tests/features/test_images.h"

namespace duskmap {
namespace {

TEST(BriefTest, PatternIsFixedGaussianInsideThePatch) {
  const BriefOptions options;
  const auto a = MakeBriefPattern(options), b = MakeBriefPattern(options);
  ASSERT_EQ(a.size(), 256u);
  EXPECT_EQ(a, b);
  double sum_sq = 0.0;
  std::set<std::array<int8_t, 4>> unique(a.begin(), a.end());
  EXPECT_GT(unique.size(), 250u);
  for (const auto& p : a) {
    for (int8_t v : p) {
      EXPECT_LE(std::abs(v), options.patch_size_px / 2 - 1);
      sum_sq += v * v;
    }
  }
  // Pattern G II: sigma = S / 5 = 9.6 px (clipping shrinks it slightly).
  const double sigma = std::sqrt(sum_sq / (4.0 * a.size()));
  EXPECT_NEAR(sigma, options.patch_size_px / 5.0, 1.2);
  BriefOptions other = options;
  other.pattern_seed = 7;
  EXPECT_NE(MakeBriefPattern(other), a);
}

TEST(BriefTest, DescriptorsAre32BytesWithBalancedBits) {
  const BriefExtractor extractor(BriefOptions(), GfttOptions(), 1000);
  const FrameFeatures f = extractor.Extract(testing::TexturedImage());
  ASSERT_GT(f.size(), 500u);
  EXPECT_EQ(f.kind, DescriptorKind::kBinary);
  EXPECT_EQ(f.DescriptorBytes(), 32u);
  // Each test is an intensity comparison: over many keypoints bits are set
  // roughly half of the time.
  size_t ones = 0;
  for (int r = 0; r < f.descriptors.rows; ++r) {
    for (int c = 0; c < 32; ++c) ones += std::bitset<8>(f.descriptors.at<uint8_t>(r, c)).count();
  }
  const double fraction = static_cast<double>(ones) / (f.descriptors.rows * 256.0);
  EXPECT_GT(fraction, 0.35);
  EXPECT_LT(fraction, 0.65);
  // Keypoints keep the full patch inside the image.
  for (const cv::KeyPoint& kp : f.keypoints) {
    EXPECT_GE(kp.pt.x, 24.0f);
    EXPECT_LE(kp.pt.x, 640 - 25.0f);
  }
}

TEST(BriefTest, BitsFollowIntensityComparisons) {
  // On a horizontal ramp, a test is 1 exactly when its first point lies left
  // of its second one.
  cv::Mat ramp(100, 100, CV_8UC1);
  for (int x = 0; x < 100; ++x) ramp.col(x).setTo(x * 2);
  const auto pattern = MakeBriefPattern(BriefOptions());
  const cv::Mat d = DescribeBrief(ramp, {cv::KeyPoint(50, 50, 7)}, pattern);
  for (size_t i = 0; i < pattern.size(); ++i) {
    const bool bit = d.at<uint8_t>(0, static_cast<int>(i / 8)) & (1u << (i % 8));
    EXPECT_EQ(bit, pattern[i][0] < pattern[i][2]) << i;
  }
}

TEST(BriefTest, SixteenAndSixtyFourBytes) {
  for (int bytes : {16, 64}) {
    BriefOptions options;
    options.bytes = bytes;
    const FrameFeatures f =
        BriefExtractor(options, GfttOptions(), 500).Extract(testing::TexturedImage(320, 240, 4));
    ASSERT_FALSE(f.empty());
    EXPECT_EQ(f.DescriptorBytes(), static_cast<size_t>(bytes));
  }
}

}  // namespace
}  // namespace duskmap
