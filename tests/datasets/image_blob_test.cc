#include "slam/datasets/image_blob.h"

#include <gtest/gtest.h>

#include <cstring>

#include <opencv2/imgcodecs.hpp>

#include "slam/datasets/rvl_codec.h"
#include "tests/datasets/dataset_test_util.h"

namespace duskmap {
namespace {

using testing::ErrorOf;

std::vector<uint8_t> Encode(const std::string& ext, const cv::Mat& image) {
  std::vector<uint8_t> bytes;
  cv::imencode(ext, image, bytes);
  return bytes;
}

TEST(SniffBlobCodec, UsesMagicBytes) {
  const std::vector<uint8_t> jpeg = Encode(".jpg", cv::Mat(4, 4, CV_8UC3, cv::Scalar::all(9)));
  const std::vector<uint8_t> png = Encode(".png", cv::Mat(4, 4, CV_8UC1, cv::Scalar::all(9)));
  const std::vector<uint8_t> rvl = EncodeRvlBlob(cv::Mat(4, 4, CV_16UC1, cv::Scalar::all(9)));
  EXPECT_EQ(SniffBlobCodec(jpeg.data(), jpeg.size()), BlobCodec::kJpeg);
  EXPECT_EQ(SniffBlobCodec(png.data(), png.size()), BlobCodec::kPng);
  EXPECT_EQ(SniffBlobCodec(rvl.data(), rvl.size()), BlobCodec::kRvl);
  const uint8_t text[] = "hello";
  EXPECT_EQ(SniffBlobCodec(text, sizeof(text)), BlobCodec::kUnknown);
}

TEST(DecodeColorBlob, ExpandsGreyAndRejectsNonImages) {
  const std::vector<uint8_t> grey = Encode(".png", cv::Mat(3, 5, CV_8UC1, cv::Scalar::all(77)));
  const cv::Mat bgr = DecodeColorBlob(grey.data(), grey.size(), "g");
  EXPECT_EQ(bgr.type(), CV_8UC3);
  EXPECT_EQ(bgr.at<cv::Vec3b>(2, 4), cv::Vec3b(77, 77, 77));
  const std::vector<uint8_t> deep = Encode(".png", cv::Mat(3, 5, CV_16UC1, cv::Scalar::all(7)));
  EXPECT_EQ(ErrorOf([&] { DecodeColorBlob(deep.data(), deep.size(), "x"); }),
            "x: colour image is not 8-bit (OpenCV type 2)");
  const uint8_t text[] = "hello";
  EXPECT_EQ(ErrorOf([&] { DecodeColorBlob(text, sizeof(text), "x"); }),
            "x: colour image is neither JPEG nor PNG (6 bytes)");
  std::vector<uint8_t> cut = Encode(".png", cv::Mat(30, 30, CV_8UC3, cv::Scalar::all(1)));
  cut.resize(cut.size() - 20);
  EXPECT_EQ(ErrorOf([&] { DecodeColorBlob(cut.data(), cut.size(), "x"); }),
            "x: PNG is truncated (no IEND chunk)");
}

// A header may declare any size; the decoder would allocate it (found by
// fuzzing the database reader: a 3-kB blob asked for 2.6 GB). Such blobs are
// refused before decoding, naming the declared size.
TEST(DecodeColorBlob, RefusesImagesDeclaringMoreThanTheLimit) {
  std::vector<uint8_t> png = Encode(".png", cv::Mat(8, 8, CV_8UC3, cv::Scalar::all(5)));
  ASSERT_EQ(std::memcmp(png.data() + 12, "IHDR", 4), 0);
  const uint8_t huge[4] = {0x00, 0x00, 0xC3, 0x50};  // 50000
  std::memcpy(png.data() + 16, huge, 4);
  std::memcpy(png.data() + 20, huge, 4);
  EXPECT_EQ(ErrorOf([&] { DecodeColorBlob(png.data(), png.size(), "x"); }),
            "x: PNG declares 50000x50000 pixels, more than the 67108864-pixel limit");
  std::vector<uint8_t> jpeg = Encode(".jpg", cv::Mat(8, 8, CV_8UC3, cv::Scalar::all(5)));
  size_t sof = 0;
  for (size_t i = 2; i + 1 < jpeg.size(); ++i) {
    if (jpeg[i] == 0xFF && jpeg[i + 1] == 0xC0) {
      sof = i;
      break;
    }
  }
  ASSERT_GT(sof, 0u);
  jpeg[sof + 5] = 0xC3;  // height 50000
  jpeg[sof + 6] = 0x50;
  jpeg[sof + 7] = 0xC3;  // width 50000
  jpeg[sof + 8] = 0x50;
  EXPECT_EQ(ErrorOf([&] { DecodeColorBlob(jpeg.data(), jpeg.size(), "x"); }),
            "x: JPEG declares 50000x50000 pixels, more than the 67108864-pixel limit");
  // The largest sides a PNG header can hold: judged without overflowing.
  const uint8_t widest[4] = {0xFF, 0xFF, 0xFF, 0xFF};
  std::memcpy(png.data() + 16, widest, 4);
  std::memcpy(png.data() + 20, widest, 4);
  EXPECT_EQ(ErrorOf([&] { DecodeColorBlob(png.data(), png.size(), "x"); }),
            "x: PNG declares 4294967295x4294967295 pixels, more than the 67108864-pixel limit");
  // Images within the limit still decode.
  const std::vector<uint8_t> fine = Encode(".jpg", cv::Mat(8, 8, CV_8UC3, cv::Scalar::all(5)));
  EXPECT_EQ(DecodeColorBlob(fine.data(), fine.size(), "x").size(), cv::Size(8, 8));
}

TEST(DecodeDepthBlob, ReadsMillimetresRvlAndFloatPng) {
  cv::Mat mm = (cv::Mat_<uint16_t>(1, 3) << 0, 1500, 65535);
  const std::vector<uint8_t> png = Encode(".png", mm);
  const cv::Mat from_png = DecodeDepthBlob(png.data(), png.size(), "d");
  ASSERT_EQ(from_png.type(), CV_32FC1);
  EXPECT_FLOAT_EQ(from_png.at<float>(0, 1), 1.5f);
  EXPECT_FLOAT_EQ(from_png.at<float>(0, 0), 0.0f);
  const std::vector<uint8_t> rvl = EncodeRvlBlob(mm);
  EXPECT_EQ(cv::norm(DecodeDepthBlob(rvl.data(), rvl.size(), "d"), from_png, cv::NORM_INF), 0.0);
  // Float metres packed as 8UC4, as RTAB-Map stores float depth.
  const cv::Mat metres = (cv::Mat_<float>(1, 3) << 0.25f, 0.0f, 7.125f);
  cv::Mat packed(1, 3, CV_8UC4);
  std::memcpy(packed.data, metres.data, 12);
  const std::vector<uint8_t> float_png = Encode(".png", packed);
  const cv::Mat decoded = DecodeDepthBlob(float_png.data(), float_png.size(), "d");
  EXPECT_EQ(cv::norm(decoded, metres, cv::NORM_INF), 0.0);
}

}  // namespace
}  // namespace duskmap
