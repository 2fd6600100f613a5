#include "slam/synthetic/raster/mip_texture.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "slam/core/check.h"

namespace duskmap {
namespace {

// Texture coordinates of the centre of texel (col, row) (v up).
double U(double col, int width) { return (col + 0.5) / width; }
double V(double row, int height) { return 1.0 - (row + 0.5) / height; }

void ExpectNear(const cv::Vec3f& actual, const cv::Vec3f& expected, double tolerance) {
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(actual[k], expected[k], tolerance) << "channel " << k;
}

cv::Vec3f Mean(const cv::Mat& image) {
  const cv::Scalar m = cv::mean(image);
  return cv::Vec3f(static_cast<float>(m[0]), static_cast<float>(m[1]), static_cast<float>(m[2]));
}

TEST(MipTexture, ConstantTextureSamplesConstantAtEveryLevel) {
  const cv::Vec3f color(0.2f, 0.5f, 0.9f);
  const MipTexture texture(cv::Mat(23, 37, CV_32FC3, cv::Scalar(color[0], color[1], color[2])));
  ASSERT_EQ(texture.num_levels(), 6);  // 37x23, 18x11, 9x5, 4x2, 2x1, 1x1
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> coordinate(-3.0, 3.0);
  for (const double footprint : {0.0, 0.5, 1.0, 1.7, 2.0, 5.0, 33.0, 1e3, 1e9}) {
    for (int i = 0; i < 50; ++i) {
      ExpectNear(texture.Sample(coordinate(rng), coordinate(rng), footprint), color, 1e-6);
    }
  }
  for (int level = 0; level < texture.num_levels(); ++level) ExpectNear(Mean(texture.level(level)), color, 1e-6);
}

TEST(MipTexture, CheckerboardOfSingleTexelsAveragesToItsMeanAtLargeFootprints) {
  cv::Mat checker(64, 64, CV_32FC3);
  for (int row = 0; row < 64; ++row) {
    for (int col = 0; col < 64; ++col) checker.at<cv::Vec3f>(row, col) = cv::Vec3f::all((row + col) % 2);
  }
  const MipTexture texture(checker);
  ASSERT_EQ(texture.num_levels(), 7);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> coordinate(0.0, 1.0);
  for (const double footprint : {2.0, 3.0, 8.0, 64.0, 1e6}) {
    for (int i = 0; i < 50; ++i) {
      ExpectNear(texture.Sample(coordinate(rng), coordinate(rng), footprint), cv::Vec3f::all(0.5f), 1e-6);
    }
  }
  // At level 0 a texel centre reads its texel: top-left (row 0, col 0) is black.
  ExpectNear(texture.Sample(U(0, 64), V(0, 64), 1.0), cv::Vec3f::all(0.0f), 1e-6);
  ExpectNear(texture.Sample(U(1, 64), V(0, 64), 1.0), cv::Vec3f::all(1.0f), 1e-6);
}

TEST(MipTexture, BilinearIsExactOnALinearRampAtLevelZero) {
  const int width = 16, height = 9;
  cv::Mat ramp(height, width, CV_32FC3);
  auto value = [](double x, double y) { return cv::Vec3f(0.1 * x, 0.05 * y, 0.01 * x + 0.02 * y + 0.3); };
  for (int row = 0; row < height; ++row) {
    for (int col = 0; col < width; ++col) ramp.at<cv::Vec3f>(row, col) = value(col, row);
  }
  const MipTexture texture(ramp);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> x(0.0, width - 1.0), y(0.0, height - 1.0);
  for (int i = 0; i < 200; ++i) {
    const double col = x(rng), row = y(rng);
    ExpectNear(texture.Sample(U(col, width), V(row, height), 0.8), value(col, row), 1e-5);
  }
}

TEST(MipTexture, VIsUpSoVZeroIsTheImagesBottomRow) {
  cv::Mat image(4, 3, CV_32FC3, cv::Scalar::all(0.5));
  image.row(0).setTo(cv::Scalar(1, 0, 0));
  image.row(3).setTo(cv::Scalar(0, 0, 1));
  const MipTexture texture(image);
  ExpectNear(texture.Sample(U(1, 3), V(0, 4), 1.0), cv::Vec3f(1, 0, 0), 1e-6);
  ExpectNear(texture.Sample(U(1, 3), 0.5 / 4, 1.0), cv::Vec3f(0, 0, 1), 1e-6);  // v near 0: bottom
  ExpectNear(texture.Sample(U(1, 3), 1.0 - 0.5 / 4, 1.0), cv::Vec3f(1, 0, 0), 1e-6);  // v near 1: top
}

TEST(MipTexture, AddressingWrapsAround) {
  const int width = 5, height = 4;
  cv::Mat image(height, width, CV_32FC3);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  for (int row = 0; row < height; ++row) {
    for (int col = 0; col < width; ++col) image.at<cv::Vec3f>(row, col) = cv::Vec3f(unit(rng), unit(rng), unit(rng));
  }
  const MipTexture texture(image);
  std::uniform_real_distribution<double> coordinate(0.0, 1.0);
  for (int i = 0; i < 100; ++i) {
    const double u = coordinate(rng), v = coordinate(rng);
    const cv::Vec3f s = texture.Sample(u, v, 1.0);
    ExpectNear(texture.Sample(u + 1.0, v, 1.0), s, 1e-5);
    ExpectNear(texture.Sample(u - 3.0, v + 2.0, 1.0), s, 1e-5);
    ExpectNear(texture.Sample(u, v - 1.0, 1.0), s, 1e-5);
  }
  // u = 0 lies halfway between the last and the first column; v = 1 between
  // the top and the bottom row.
  const cv::Vec3f left = image.at<cv::Vec3f>(1, 0), right = image.at<cv::Vec3f>(1, width - 1);
  ExpectNear(texture.Sample(0.0, V(1, height), 1.0), (left + right) * 0.5f, 1e-6);
  const cv::Vec3f top = image.at<cv::Vec3f>(0, 2), bottom = image.at<cv::Vec3f>(height - 1, 2);
  ExpectNear(texture.Sample(U(2, width), 1.0, 1.0), (top + bottom) * 0.5f, 1e-6);
}

TEST(MipTexture, OddSizesBuildDownToOneByOneKeepingTheMean) {
  cv::Mat image(3, 5, CV_32FC3);
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  for (int row = 0; row < 3; ++row) {
    for (int col = 0; col < 5; ++col) image.at<cv::Vec3f>(row, col) = cv::Vec3f(unit(rng), unit(rng), unit(rng));
  }
  const MipTexture texture(image);
  ASSERT_EQ(texture.num_levels(), 3);
  EXPECT_EQ(texture.level(1).size(), cv::Size(2, 1));
  EXPECT_EQ(texture.level(2).size(), cv::Size(1, 1));
  const cv::Vec3f mean = Mean(image);
  for (int level = 0; level < 3; ++level) ExpectNear(Mean(texture.level(level)), mean, 1e-6);
  // Level 1, texel 0 averages columns 0, 1 and half of 2 of all three rows.
  cv::Vec3f expected(0, 0, 0);
  for (int row = 0; row < 3; ++row) {
    expected += image.at<cv::Vec3f>(row, 0) + image.at<cv::Vec3f>(row, 1) + image.at<cv::Vec3f>(row, 2) * 0.5f;
  }
  ExpectNear(texture.level(1).at<cv::Vec3f>(0, 0), expected / 7.5f, 1e-6);
  ExpectNear(texture.Sample(0.3, 0.6, 1e6), mean, 1e-6);

  const MipTexture single(cv::Mat(1, 1, CV_32FC3, cv::Scalar(0.25, 0.5, 0.75)));
  EXPECT_EQ(single.num_levels(), 1);
  ExpectNear(single.Sample(0.9, -0.2, 50.0), cv::Vec3f(0.25f, 0.5f, 0.75f), 1e-7);
  const MipTexture strip(cv::Mat(1, 7, CV_32FC3, cv::Scalar::all(1.0)));
  ASSERT_EQ(strip.num_levels(), 3);  // 7x1, 3x1, 1x1
  EXPECT_EQ(strip.level(1).size(), cv::Size(3, 1));
}

TEST(MipTexture, BlendsTheTwoNearestLevelsByTheLogOfTheFootprint) {
  cv::Mat image(8, 8, CV_32FC3);
  std::mt19937 rng(13);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  for (int row = 0; row < 8; ++row) {
    for (int col = 0; col < 8; ++col) image.at<cv::Vec3f>(row, col) = cv::Vec3f(unit(rng), unit(rng), unit(rng));
  }
  const MipTexture texture(image);
  const double u = 0.37, v = 0.81;
  const cv::Vec3f l1 = texture.SampleLevel(1, u, v), l2 = texture.SampleLevel(2, u, v);
  ExpectNear(texture.Sample(u, v, 2.0), l1, 1e-6);
  ExpectNear(texture.Sample(u, v, 4.0), l2, 1e-6);
  ExpectNear(texture.Sample(u, v, std::pow(2.0, 1.25)), l1 * 0.75f + l2 * 0.25f, 1e-6);
  ExpectNear(texture.Sample(u, v, 0.1), texture.SampleLevel(0, u, v), 1e-7);
  ExpectNear(texture.Sample(u, v, std::nan("")), texture.SampleLevel(0, u, v), 1e-7);
  ExpectNear(texture.Sample(u, v, 1e30), texture.SampleLevel(3, u, v), 1e-7);
  ExpectNear(texture.Sample(std::nan(""), v, 1.0), texture.Sample(0.0, v, 1.0), 1e-7);
}

TEST(MipTexture, RejectsImagesThatAreNotNonEmptyFloatBgr) {
  EXPECT_THROW(MipTexture(cv::Mat()), InputError);
  EXPECT_THROW(MipTexture(cv::Mat(4, 4, CV_8UC3, cv::Scalar::all(0))), InputError);
  EXPECT_THROW(MipTexture(cv::Mat(4, 4, CV_32FC1, cv::Scalar::all(0))), InputError);
  EXPECT_TRUE(MipTexture().empty());
}

TEST(FootprintTexels, IsTheLongerDerivativeVectorInTexels) {
  EXPECT_DOUBLE_EQ(FootprintTexels(0.01, 0.0, 0.0, 0.02, 100, 100), 2.0);
  EXPECT_DOUBLE_EQ(FootprintTexels(0.03, 0.04, 0.0, 0.0, 100, 100), 5.0);
  EXPECT_DOUBLE_EQ(FootprintTexels(0.0, 0.0, 0.01, -0.01, 300, 400), 5.0);
  EXPECT_DOUBLE_EQ(FootprintTexels(0.0, 0.0, 0.0, 0.0, 64, 64), 0.0);
}

}  // namespace
}  // namespace duskmap
