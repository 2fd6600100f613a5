#include "slam/datasets/calibration_blob.h"

#include <gtest/gtest.h>

#include <cstring>

#include "tests/datasets/dataset_test_util.h"

namespace duskmap {
namespace {

using testing::ErrorOf;

template <typename T>
void Append(T value, std::vector<uint8_t>* out) {
  const auto* p = reinterpret_cast<const uint8_t*>(&value);
  out->insert(out->end(), p, p + sizeof(T));
}

// A mono record with K, nD distortion values and an identity local transform.
std::vector<uint8_t> MonoRecord(int type, const std::vector<double>& distortion) {
  std::vector<uint8_t> blob;
  for (int v : {0, 23, 8, type, 640, 480, 9, static_cast<int>(distortion.size()), 0, 0, 12}) {
    Append<int32_t>(v, &blob);
  }
  for (double v : {500.0, 0.0, 320.0, 0.0, 501.0, 240.0, 0.0, 0.0, 1.0}) Append(v, &blob);
  for (double v : distortion) Append(v, &blob);
  for (float v : {1.f, 0.f, 0.f, 0.1f, 0.f, 1.f, 0.f, 0.f, 0.f, 0.f, 1.f, 0.f}) Append(v, &blob);
  return blob;
}

TEST(ParseCalibrationBlob, ReadsMonoRecordWithFisheyeDistortion) {
  const std::vector<uint8_t> blob = MonoRecord(0, {0.1, 0.2, 0.0, 0.0, 0.3, 0.4});
  const CameraCalibration c = ParseCalibrationBlob(blob.data(), blob.size(), "c");
  EXPECT_EQ(c.image_width, 640);
  EXPECT_DOUBLE_EQ(c.Pinhole().fy, 501.0);
  EXPECT_TRUE(c.fisheye);
  EXPECT_EQ(c.distortion, (std::vector<double>{0.1, 0.2, 0.3, 0.4}));
  EXPECT_NEAR(c.body_from_camera.translation.x(), 0.1, 1e-7);
}

TEST(ParseCalibrationBlob, RejectsStereoMultiCameraAndBadCounts) {
  const std::vector<uint8_t> stereo = MonoRecord(1, {});
  EXPECT_EQ(ErrorOf([&] { ParseCalibrationBlob(stereo.data(), stereo.size(), "c"); }),
            "c: stereo calibration is not supported");
  std::vector<uint8_t> two = MonoRecord(0, {});
  const std::vector<uint8_t> one = two;
  two.insert(two.end(), one.begin(), one.end());
  EXPECT_NE(ErrorOf([&] { ParseCalibrationBlob(two.data(), two.size(), "c"); })
                .find("multi-camera rigs are not supported"),
            std::string::npos);
  std::vector<uint8_t> bad = MonoRecord(0, {});
  const int32_t nine_hundred = 900;
  std::memcpy(bad.data() + 28, &nine_hundred, 4);  // nD
  EXPECT_NE(ErrorOf([&] { ParseCalibrationBlob(bad.data(), bad.size(), "c"); })
                .find("invalid element counts"),
            std::string::npos);
}

TEST(ParseTransformBlob, NullAndMalformedTransforms) {
  const std::vector<uint8_t> zeros(48, 0);
  EXPECT_FALSE(ParseTransformBlob(zeros.data(), zeros.size(), "t").has_value());
  EXPECT_EQ(ErrorOf([&] { ParseTransformBlob(zeros.data(), 47, "t"); }),
            "t: transform blob has 47 bytes, expected 48");
}

}  // namespace
}  // namespace duskmap
