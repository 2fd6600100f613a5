#include "slam/features/binary_distance.h"

#include <cstdlib>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "slam/core/check.h"
#include "slam/core/random.h"

namespace duskmap {
namespace {

TEST(BinaryDistance, ByteL1AndHammingMatchTheirDefinitions) {
  Rng rng(5);
  for (int cols = 1; cols <= 70; ++cols) {
    std::vector<uint8_t> a(cols), b(cols);
    for (int i = 0; i < cols; ++i) {
      a[i] = static_cast<uint8_t>(rng());
      b[i] = static_cast<uint8_t>(rng());
    }
    uint32_t l1 = 0;
    for (int i = 0; i < cols; ++i) l1 += static_cast<uint32_t>(std::abs(int{a[i]} - int{b[i]}));
    EXPECT_EQ(ByteL1Distance(a.data(), b.data(), cols), l1) << cols << " bytes";
    const cv::Mat ma(1, cols, CV_8U, a.data()), mb(1, cols, CV_8U, b.data());
    EXPECT_EQ(HammingDistance(a.data(), b.data(), cols),
              static_cast<uint32_t>(cv::norm(ma, mb, cv::NORM_HAMMING)))
        << cols << " bytes";
  }
  // The extremes: 32 bytes 0 against 255 is 32 x 255 by L1, 256 bits.
  const std::vector<uint8_t> zeros(32, 0), ones(32, 255);
  EXPECT_EQ(ByteL1Distance(zeros.data(), ones.data(), 32), 32u * 255u);
  EXPECT_EQ(HammingDistance(zeros.data(), ones.data(), 32), 256u);
}

TEST(BinaryDistance, TheTwoOrderNeighboursDifferently) {
  // One flipped high bit: Hamming 1, L1 128. Three flipped low bits: Hamming
  // 3, L1 1 + 2 + 4 = 7.
  const uint8_t q[2] = {0x00, 0x00};
  const uint8_t high[2] = {0x80, 0x00};
  const uint8_t low[2] = {0x07, 0x00};
  EXPECT_LT(HammingDistance(q, high, 2), HammingDistance(q, low, 2));
  EXPECT_GT(ByteL1Distance(q, high, 2), ByteL1Distance(q, low, 2));
  EXPECT_EQ(BinaryRowDistance(BinaryDistance::kByteL1, q, low, 2), 7u);
  EXPECT_EQ(BinaryRowDistance(BinaryDistance::kHamming, q, low, 2), 3u);
}

TEST(BinaryDistance, NamesRoundTripAndBadNamesAreRefused) {
  for (BinaryDistance d : {BinaryDistance::kHamming, BinaryDistance::kByteL1}) {
    EXPECT_EQ(ParseBinaryDistance(BinaryDistanceName(d), "x"), d);
  }
  try {
    ParseBinaryDistance("l2", "EngineOptions.binary_distance");
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("EngineOptions.binary_distance"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("byte_l1"), std::string::npos);
  }
}

}  // namespace
}  // namespace duskmap
