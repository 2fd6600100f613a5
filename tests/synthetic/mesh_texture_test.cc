#include "slam/synthetic/assets/mesh_texture.h"

#include <gtest/gtest.h>

#include "mesh_test_files.h"
#include "slam/core/check.h"
#include "slam/io/image_header.h"

namespace duskmap {
namespace {

TEST(SrgbToLinear, MatchesTheStandardCurve) {
  EXPECT_FLOAT_EQ(SrgbToLinear(0.0f), 0.0f);
  EXPECT_FLOAT_EQ(SrgbToLinear(1.0f), 1.0f);
  EXPECT_NEAR(SrgbToLinear(0.04f), 0.04f / 12.92f, 1e-7);
  EXPECT_NEAR(SrgbToLinear(128.0f / 255.0f), 0.2158605f, 1e-6);
}

TEST(DecodeSrgbTexture, DecodesPngAndJpegToLinearBgr) {
  cv::Mat image(2, 3, CV_8UC3, cv::Scalar(0, 128, 255));  // B G R
  image.at<cv::Vec3b>(1, 2) = cv::Vec3b(255, 255, 255);
  const cv::Mat png = DecodeSrgbTexture(EncodeImage(image, ".png"), "t.png", kMaxImagePixels);
  ASSERT_EQ(png.type(), CV_32FC3);
  ASSERT_EQ(png.size(), cv::Size(3, 2));
  EXPECT_FLOAT_EQ(png.at<cv::Vec3f>(0, 0)[0], 0.0f);
  EXPECT_NEAR(png.at<cv::Vec3f>(0, 0)[1], 0.2158605f, 1e-6);
  EXPECT_FLOAT_EQ(png.at<cv::Vec3f>(0, 0)[2], 1.0f);
  EXPECT_FLOAT_EQ(png.at<cv::Vec3f>(1, 2)[0], 1.0f);

  const cv::Mat grey(8, 8, CV_8UC1, cv::Scalar(128));
  const cv::Mat jpeg = DecodeSrgbTexture(EncodeImage(grey, ".jpg"), "t.jpg", kMaxImagePixels);
  ASSERT_EQ(jpeg.type(), CV_32FC3);
  EXPECT_NEAR(jpeg.at<cv::Vec3f>(4, 4)[2], 0.2158605f, 0.01);
}

TEST(DecodeSrgbTexture, RefusesAnOversizedHeaderBeforeDecoding) {
  EXPECT_EQ(InputErrorOf([] { DecodeSrgbTexture(PngHeader(20000, 10000), "big.png", kMaxImagePixels); }),
            "big.png: 20000x10000 texture exceeds the limit of 67108864 pixels");
  const cv::Mat image(4, 4, CV_8UC3, cv::Scalar(1, 2, 3));
  EXPECT_EQ(InputErrorOf([&] { DecodeSrgbTexture(EncodeImage(image, ".png"), "small.png", 15); }),
            "small.png: 4x4 texture exceeds the limit of 15 pixels");
}

TEST(DecodeSrgbTexture, RefusesUndecodableBytes) {
  EXPECT_EQ(InputErrorOf([] { DecodeSrgbTexture("not an image", "x.png", kMaxImagePixels); }),
            "x.png: texture cannot be decoded (not a readable image)");
  EXPECT_EQ(InputErrorOf([] { DecodeSrgbTexture("", "x.png", kMaxImagePixels); }),
            "x.png: texture cannot be decoded (empty file)");
  const std::string cut = PngHeader(4, 4);  // a header but no image data
  const std::string message = InputErrorOf([&] { DecodeSrgbTexture(cut, "cut.png", kMaxImagePixels); });
  EXPECT_EQ(message.rfind("cut.png: texture cannot be decoded", 0), 0u) << message;
}

}  // namespace
}  // namespace duskmap
