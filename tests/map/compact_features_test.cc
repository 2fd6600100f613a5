// Compact node features: quantization error bounds, exact binary rows,
// packed keypoints and half-float points, and the errors for bad input.
#include "slam/map/compact_features.h"

#include <cmath>

#include <gtest/gtest.h>

#include "slam/core/check.h"

namespace duskmap {
namespace {

FrameFeatures SurfLikeFeatures(int n) {
  cv::RNG rng(3);
  FrameFeatures f;
  f.kind = DescriptorKind::kFloat;
  f.descriptors = cv::Mat(n, 64, CV_32F);
  rng.fill(f.descriptors, cv::RNG::NORMAL, 0.0, 0.1);
  for (int r = 0; r < n; ++r) cv::normalize(f.descriptors.row(r), f.descriptors.row(r));
  for (int i = 0; i < n; ++i) {
    f.keypoints.emplace_back(639.93f * i / n, 479.1f - i, 12.3f + i, i % 3 ? 359.99f * i / n : -1.f,
                             0.5f / (i + 1), i, 7);
    f.points_in_camera.push_back(i % 4 == 0 ? Eigen::Vector3f::Constant(std::nanf(""))
                                            : Eigen::Vector3f(0.3f * i, -1.7f, 0.4f + 0.9f * i));
  }
  return f;
}

TEST(CompactFeatures, QuantizedDescriptorsStayWithinHalfAStep) {
  const FrameFeatures f = SurfLikeFeatures(20);
  const CompactFeatures c = CompactFeatures::Encode(f, DescriptorStorage::kUint8);
  EXPECT_EQ(c.DescriptorBytes(), 256u);  // as extracted
  EXPECT_EQ(c.DescriptorMemoryBytes(), 20u * (64 + 8));
  const FrameFeatures d = c.Decode();
  ASSERT_EQ(d.descriptors.type(), CV_32F);
  ASSERT_EQ(d.descriptors.size(), f.descriptors.size());
  for (int r = 0; r < 20; ++r) {
    const double step = c.row_steps()[r];
    EXPECT_GT(step, 0.0);
    EXPECT_LE(cv::norm(d.descriptors.row(r), f.descriptors.row(r), cv::NORM_INF), 0.5 * step + 1e-6);
  }
  // Distances between rows, which matching compares, move by well under 1 %.
  const double exact = cv::norm(f.descriptors.row(0), f.descriptors.row(1));
  const double decoded = cv::norm(d.descriptors.row(0), d.descriptors.row(1));
  EXPECT_NEAR(decoded, exact, 0.01 * exact);
}

TEST(CompactFeatures, Float32StorageAndBinaryRowsAreExact) {
  const FrameFeatures f = SurfLikeFeatures(10);
  const FrameFeatures d = CompactFeatures::Encode(f, DescriptorStorage::kFloat32).Decode();
  EXPECT_EQ(cv::norm(d.descriptors, f.descriptors, cv::NORM_INF), 0.0);
  FrameFeatures binary = f;
  binary.kind = DescriptorKind::kBinary;
  binary.descriptors = cv::Mat(10, 32, CV_8U);
  cv::randu(binary.descriptors, 0, 255);
  const CompactFeatures c = CompactFeatures::Encode(binary, DescriptorStorage::kUint8);
  EXPECT_TRUE(c.row_steps().empty());
  EXPECT_EQ(c.DescriptorBytes(), 32u);
  EXPECT_EQ(cv::norm(c.Decode().descriptors, binary.descriptors, cv::NORM_INF), 0.0);
}

TEST(CompactFeatures, KeypointsAndPointsArePackedClosely) {
  const FrameFeatures f = SurfLikeFeatures(20);
  const CompactFeatures c = CompactFeatures::Encode(f, DescriptorStorage::kUint8);
  EXPECT_EQ(c.KeypointPointMemoryBytes(), 20u * (8 + 4 + 6));
  const FrameFeatures d = c.Decode();
  for (int i = 0; i < 20; ++i) {
    const cv::KeyPoint &a = f.keypoints[i], &b = d.keypoints[i];
    EXPECT_LE(std::abs(a.pt.x - b.pt.x), 1.0f / 16 + 1e-4f);
    EXPECT_LE(std::abs(a.pt.y - b.pt.y), 1.0f / 16 + 1e-4f);
    EXPECT_LE(std::abs(a.size - b.size), 1.0f / 16 + 1e-4f);
    if (a.angle < 0) {
      EXPECT_EQ(b.angle, -1.0f);
    } else {
      const float diff = std::abs(a.angle - b.angle);
      EXPECT_LE(std::min(diff, 360.0f - diff), 1.0f / 180 + 1e-4f) << a.angle << " " << b.angle;
    }
    EXPECT_EQ(a.response, b.response);
    EXPECT_EQ(b.octave, 0);  // not kept
    EXPECT_EQ(b.class_id, -1);
    EXPECT_EQ(f.HasPoint(i), d.HasPoint(i));
    EXPECT_EQ(f.HasPoint(i), c.HasPoint(i));
    if (f.HasPoint(i)) {
      EXPECT_LE((f.points_in_camera[i] - d.points_in_camera[i]).cwiseAbs().maxCoeff(),
                f.points_in_camera[i].cwiseAbs().maxCoeff() / 2048.0f);
    }
  }
}

TEST(CompactFeatures, BadInputThrows) {
  FrameFeatures f = SurfLikeFeatures(5);
  f.keypoints[2].pt.x = 9000.0f;  // beyond the packed range
  EXPECT_THROW(CompactFeatures::Encode(f, DescriptorStorage::kUint8), InputError);
  f = SurfLikeFeatures(5);
  f.points_in_camera.pop_back();
  EXPECT_THROW(CompactFeatures::Encode(f, DescriptorStorage::kUint8), InputError);
  f = SurfLikeFeatures(5);
  f.descriptors = f.descriptors.rowRange(0, 4).clone();
  EXPECT_THROW(CompactFeatures::Encode(f, DescriptorStorage::kFloat32), InputError);
  f = SurfLikeFeatures(5);
  f.descriptors.at<float>(3, 17) = std::nanf("");  // not the row's first value
  EXPECT_THROW(CompactFeatures::Encode(f, DescriptorStorage::kUint8), InputError);
  EXPECT_THROW(CompactFeatures::FromParts(DescriptorKind::kFloat, DescriptorStorage::kUint8, CV_32F,
                                          cv::Mat(2, 64, CV_8U), {0.f}, {0.f},
                                          std::vector<PackedKeypoint>(2), std::vector<float>(2),
                                          std::vector<uint16_t>(6)),
               InputError);
  EXPECT_THROW(CompactFeatures::FromParts(DescriptorKind::kBinary, DescriptorStorage::kFloat32,
                                          CV_8U, cv::Mat(2, 32, CV_8U), {}, {},
                                          std::vector<PackedKeypoint>(2), std::vector<float>(1),
                                          std::vector<uint16_t>(6)),
               InputError);  // a response missing
  EXPECT_THROW(ParseDescriptorStorage("float16"), ConfigError);
  EXPECT_EQ(ParseDescriptorStorage("uint8"), DescriptorStorage::kUint8);
}

// A localizer whose matcher does not read responses drops them: 4 bytes
// fewer per feature, everything else decoded as before.
TEST(CompactFeatures, DroppedResponsesDecodeAsZeroAndFreeTheirBytes) {
  const FrameFeatures f = SurfLikeFeatures(20);
  CompactFeatures c = CompactFeatures::Encode(f, DescriptorStorage::kUint8);
  const FrameFeatures kept = c.Decode();
  EXPECT_TRUE(c.has_responses());
  c.DropKeypointResponses();
  EXPECT_FALSE(c.has_responses());
  EXPECT_EQ(c.KeypointPointMemoryBytes(), 20u * (8 + 6));
  const FrameFeatures dropped = c.Decode();
  for (int i = 0; i < 20; ++i) {
    EXPECT_EQ(dropped.keypoints[i].response, 0.0f);
    EXPECT_EQ(dropped.keypoints[i].pt, kept.keypoints[i].pt);
    EXPECT_EQ(dropped.keypoints[i].angle, kept.keypoints[i].angle);
  }
  EXPECT_EQ(cv::norm(dropped.descriptors, kept.descriptors, cv::NORM_INF), 0.0);
}

}  // namespace
}  // namespace duskmap
