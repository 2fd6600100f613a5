#include "slam/registration/nndr_matcher.h"

#include <set>

#include <gtest/gtest.h>

#include "slam/core/check.h"
#include "tests/registration/synthetic_pair.h"

namespace duskmap {
namespace {

FrameFeatures FloatFeatures(const std::vector<std::vector<float>>& rows) {
  FrameFeatures f;
  f.kind = DescriptorKind::kFloat;
  for (const std::vector<float>& r : rows) {
    f.keypoints.emplace_back(cv::Point2f(0, 0), 1.0f);
    f.descriptors.push_back(cv::Mat(r, true).reshape(1, 1));
  }
  return f;
}

TEST(NndrMatcher, RatioAppliesToSquaredDistance) {
  // Query at the origin; nearest train at distance 0.7, second at 1.0.
  // Plain ratio 0.7 fails 0.6; squared ratio 0.49 passes it.
  const FrameFeatures query = FloatFeatures({{0.0f, 0.0f}});
  const FrameFeatures train = FloatFeatures({{0.7f, 0.0f}, {0.0f, 1.0f}});
  const std::vector<cv::DMatch> matches = NndrMatcher().Match(query, {}, train, {});
  ASSERT_EQ(matches.size(), 1u);
  EXPECT_EQ(matches[0].queryIdx, 0);
  EXPECT_EQ(matches[0].trainIdx, 0);
  EXPECT_NEAR(matches[0].distance, 0.49f, 1e-6);
  // 0.8 / 1.0 -> 0.64 on squared distance: rejected at 0.6.
  const FrameFeatures far = FloatFeatures({{0.8f, 0.0f}, {0.0f, 1.0f}});
  EXPECT_TRUE(NndrMatcher().Match(query, {}, far, {}).empty());
}

TEST(NndrMatcher, UniquenessDropsSharedMapFeature) {
  const FrameFeatures query = FloatFeatures({{0.0f, 0.0f}, {0.05f, 0.0f}, {5.0f, 5.0f}});
  const FrameFeatures train = FloatFeatures({{0.01f, 0.0f}, {3.0f, 0.0f}, {5.0f, 5.1f}});
  const std::vector<cv::DMatch> unique = NndrMatcher().Match(query, {}, train, {});
  ASSERT_EQ(unique.size(), 1u);  // queries 0 and 1 both chose train 0: both dropped
  EXPECT_EQ(unique[0].queryIdx, 2);
  EXPECT_EQ(unique[0].trainIdx, 2);
  NndrMatcherOptions options;
  options.unique = false;
  EXPECT_EQ(NndrMatcher(options).Match(query, {}, train, {}).size(), 3u);
}

TEST(NndrMatcher, KdTreeAgreesWithBruteForce) {
  testing::SyntheticPairOptions data;
  data.num_points = 500;
  const testing::SyntheticPair pair = testing::MakeSyntheticPair(data);
  NndrMatcherOptions brute, tree;
  brute.search = NndrSearch::kBruteForce;
  tree.search = NndrSearch::kKdTree;
  const auto a = NndrMatcher(brute).Match(pair.query, {}, pair.map_node, {});
  const auto b = NndrMatcher(tree).Match(pair.query, {}, pair.map_node, {});
  std::set<std::pair<int, int>> sa, sb;
  for (const auto& m : a) sa.insert({m.queryIdx, m.trainIdx});
  for (const auto& m : b) sb.insert({m.queryIdx, m.trainIdx});
  size_t common = 0;
  for (const auto& m : sb) common += sa.count(m);
  EXPECT_GT(a.size(), 450u);
  EXPECT_GT(common, 0.95 * a.size());
  EXPECT_EQ(common, sb.size());  // the approximate search never invents a match here
}

TEST(NndrMatcher, BinaryUsesHamming) {
  testing::SyntheticPairOptions data;
  data.kind = DescriptorKind::kBinary;
  const testing::SyntheticPair pair = testing::MakeSyntheticPair(data);
  const auto matches = NndrMatcher().Match(pair.query, {}, pair.map_node, {});
  EXPECT_EQ(matches.size(), pair.query.size());
  for (const cv::DMatch& m : matches) {
    EXPECT_EQ(m.distance, DescriptorDistance(pair.query.descriptors, m.queryIdx,
                                             pair.map_node.descriptors, m.trainIdx,
                                             DescriptorKind::kBinary));
    EXPECT_LE(m.distance, 6.0f);  // six flipped bits
  }
}

TEST(NndrMatcher, BinaryByteL1OrdersByByteValues) {
  // Query 0x00; train rows: one high bit flipped (Hamming 1, L1 128), three
  // low bits flipped (Hamming 3, L1 7), and a far row. Hamming picks the
  // first, byte L1 the second.
  auto binary = [](const std::vector<std::vector<uint8_t>>& rows) {
    FrameFeatures f;
    f.kind = DescriptorKind::kBinary;
    for (const auto& r : rows) {
      f.keypoints.emplace_back(cv::Point2f(0, 0), 1.0f);
      f.descriptors.push_back(cv::Mat(r, true).reshape(1, 1));
    }
    return f;
  };
  const FrameFeatures query = binary({{0x00, 0x00, 0x00, 0x00}});
  const FrameFeatures train =
      binary({{0x80, 0x00, 0x00, 0x00}, {0x07, 0x00, 0x00, 0x00}, {0xff, 0xff, 0xff, 0xff}});
  NndrMatcherOptions hamming;
  hamming.binary_ratio = 0.5;
  const auto by_bits = NndrMatcher(hamming).Match(query, {}, train, {});
  ASSERT_EQ(by_bits.size(), 1u);
  EXPECT_EQ(by_bits[0].trainIdx, 0);
  EXPECT_EQ(by_bits[0].distance, 1.0f);
  NndrMatcherOptions byte_l1 = hamming;
  byte_l1.binary_distance = BinaryDistance::kByteL1;
  const auto by_bytes = NndrMatcher(byte_l1).Match(query, {}, train, {});
  ASSERT_EQ(by_bytes.size(), 1u);
  EXPECT_EQ(by_bytes[0].trainIdx, 1);
  EXPECT_EQ(by_bytes[0].distance, 7.0f);  // 7 < 0.5 x 128
}

TEST(NndrMatcher, DegenerateInputs) {
  const FrameFeatures one = FloatFeatures({{1.0f, 0.0f}});
  EXPECT_TRUE(NndrMatcher().Match(one, {}, one, {}).empty());  // no second neighbour
  EXPECT_TRUE(NndrMatcher().Match(FrameFeatures{}, {}, one, {}).empty());
  const FrameFeatures same = FloatFeatures({{1.0f, 1.0f}, {1.0f, 1.0f}, {1.0f, 1.0f}});
  EXPECT_TRUE(NndrMatcher().Match(same, {}, same, {}).empty());  // ties never pass
  FrameFeatures wrong_type = one;
  wrong_type.kind = DescriptorKind::kBinary;
  EXPECT_THROW(NndrMatcher().Match(wrong_type, {}, one, {}), InputError);
  const FrameFeatures wide = FloatFeatures({{1.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}});
  EXPECT_THROW(NndrMatcher().Match(wide, {}, same, {}), InputError);
  NndrMatcherOptions bad;
  bad.float_ratio = 1.5;
  EXPECT_THROW(NndrMatcher{bad}, ConfigError);
}

}  // namespace
}  // namespace duskmap
