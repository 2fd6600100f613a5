#include "slam/datasets/rvl_codec.h"

#include <gtest/gtest.h>

#include "slam/core/check.h"
#include "tests/datasets/dataset_test_util.h"

namespace duskmap {
namespace {

using testing::ErrorOf;

cv::Mat RandomDepth(int rows, int cols, uint64_t seed) {
  cv::RNG rng(seed);
  cv::Mat depth(rows, cols, CV_16UC1);
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      const bool hole = rng.uniform(0.0, 1.0) < 0.1 || c < 3;
      depth.at<uint16_t>(r, c) = hole ? 0 : static_cast<uint16_t>(rng.uniform(1, 65536));
    }
  }
  return depth;
}

TEST(Rvl, RoundTripsIncludingExtremeDeltasAndTrailingZeros) {
  cv::Mat depth = RandomDepth(37, 53, 7);
  depth.at<uint16_t>(5, 10) = 65535;
  depth.at<uint16_t>(5, 11) = 1;  // delta -65534
  depth.row(36).setTo(0);         // ends with a zero run
  const std::vector<uint8_t> blob = EncodeRvlBlob(depth);
  EXPECT_EQ((blob.size() - 16) % 4, 0u);
  const cv::Mat decoded = DecodeRvlBlob(blob.data(), blob.size(), "d");
  EXPECT_EQ(cv::norm(decoded, depth, cv::NORM_INF), 0.0);
}

TEST(Rvl, EncodesTheKnownNibbleLayout) {
  // 2x1 image {0, 5}: zeros=1 -> nibble 1; nonzeros=1 -> 1; delta 5 -> zig-zag
  // 10 = 0b1010 -> groups 2 (with more) then 1: nibbles 0xA, 0x1.
  cv::Mat depth = (cv::Mat_<uint16_t>(1, 2) << 0, 5);
  const std::vector<uint8_t> blob = EncodeRvlBlob(depth);
  ASSERT_EQ(blob.size(), 20u);
  EXPECT_EQ(std::string(blob.begin(), blob.begin() + 8), "DEPTHRVL");
  EXPECT_EQ(blob[8], 2);
  EXPECT_EQ(blob[12], 1);
  // Word 0x11A10000, little-endian.
  EXPECT_EQ(blob[16], 0x00);
  EXPECT_EQ(blob[17], 0x00);
  EXPECT_EQ(blob[18], 0xA1);
  EXPECT_EQ(blob[19], 0x11);
}

TEST(Rvl, RejectsTruncatedAndMalformedBlobs) {
  const cv::Mat depth = RandomDepth(20, 30, 3);
  std::vector<uint8_t> blob = EncodeRvlBlob(depth);
  std::vector<uint8_t> truncated(blob.begin(), blob.begin() + blob.size() / 2);
  truncated.resize(truncated.size() - truncated.size() % 4);
  EXPECT_EQ(ErrorOf([&] { DecodeRvlBlob(truncated.data(), truncated.size(), "x.db: node 3: depth"); }),
            "x.db: node 3: depth: RVL payload is truncated");
  std::vector<uint8_t> odd = blob;
  odd.pop_back();
  EXPECT_NE(ErrorOf([&] { DecodeRvlBlob(odd.data(), odd.size(), "d"); }).find("whole number"),
            std::string::npos);
  std::vector<uint8_t> huge = blob;
  huge[11] = 0x7F;  // width ~ 2^31
  EXPECT_NE(ErrorOf([&] { DecodeRvlBlob(huge.data(), huge.size(), "d"); }).find("out of range"),
            std::string::npos);
  std::vector<uint8_t> header_only(blob.begin(), blob.begin() + 12);
  EXPECT_NE(ErrorOf([&] { DecodeRvlBlob(header_only.data(), header_only.size(), "d"); })
                .find("header is truncated"),
            std::string::npos);
  // A zero run longer than the image.
  std::vector<uint8_t> overflow(blob.begin(), blob.begin() + 16);
  for (uint8_t b : {0x00, 0x00, 0xFF, 0xFF, 0x00, 0x00, 0x00, 0x00}) overflow.push_back(b);
  EXPECT_NE(ErrorOf([&] { DecodeRvlBlob(overflow.data(), overflow.size(), "d"); }).find("overflows"),
            std::string::npos);
}

TEST(Rvl, MatchesRtabmapBlobsByteForByte) {
  SKIP_WITHOUT_SHARED_RTABMAP(dir);
  const std::string db = dir + "/rtabmap-db/session_small.db";
  for (int id = 1; id <= 10; ++id) {
    const std::vector<uint8_t> blob =
        testing::GetBlob(db, "SELECT depth FROM Data WHERE id = " + std::to_string(id));
    ASSERT_FALSE(blob.empty());
    const cv::Mat decoded = DecodeRvlBlob(blob.data(), blob.size(), "node");
    EXPECT_EQ(EncodeRvlBlob(decoded), blob) << "node " << id;
  }
}

}  // namespace
}  // namespace duskmap
