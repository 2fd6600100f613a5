#include "slam/features/patch_sampler.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>

#include "slam/core/check.h"
#include "tests/features/test_images.h"

namespace duskmap {
namespace {

constexpr double kPi = 3.14159265358979323846;

double MeanAbsDiff(const cv::Mat& a, const cv::Mat& b) {
  cv::Mat diff;
  cv::absdiff(a, b, diff);
  return cv::mean(diff)[0];
}

cv::Point2f Apply(const cv::Mat& affine, const cv::Point2f& p) {
  return cv::Point2f(
      static_cast<float>(affine.at<double>(0, 0) * p.x + affine.at<double>(0, 1) * p.y +
                         affine.at<double>(0, 2)),
      static_cast<float>(affine.at<double>(1, 0) * p.x + affine.at<double>(1, 1) * p.y +
                         affine.at<double>(1, 2)));
}

// A reference sampler written out by hand from the header's definition, at
// level 0: bilinear, border replicated, patch +x along (cos angle, sin angle).
cv::Mat ReferencePatch(const cv::Mat& gray, const cv::KeyPoint& kp, int p, double support,
                       bool oriented = true) {
  const double step = support * kp.size / p;
  const double a = oriented ? kp.angle * kPi / 180.0 : 0.0;
  cv::Mat patch(p, p, CV_8U);
  auto at = [&](int x, int y) {
    return static_cast<double>(
        gray.at<uint8_t>(std::clamp(y, 0, gray.rows - 1), std::clamp(x, 0, gray.cols - 1)));
  };
  for (int v = 0; v < p; ++v) {
    for (int u = 0; u < p; ++u) {
      const double du = (u - 0.5 * (p - 1)) * step, dv = (v - 0.5 * (p - 1)) * step;
      const double x = kp.pt.x + du * std::cos(a) - dv * std::sin(a);
      const double y = kp.pt.y + du * std::sin(a) + dv * std::cos(a);
      const int x0 = static_cast<int>(std::floor(x)), y0 = static_cast<int>(std::floor(y));
      const double fx = x - x0, fy = y - y0;
      const double value = (1 - fy) * ((1 - fx) * at(x0, y0) + fx * at(x0 + 1, y0)) +
                           fy * ((1 - fx) * at(x0, y0 + 1) + fx * at(x0 + 1, y0 + 1));
      patch.at<uint8_t>(v, u) = cv::saturate_cast<uint8_t>(value);
    }
  }
  return patch.reshape(1, 1);
}

TEST(PatchSamplerOptions, CheckNamesTheField) {
  PatchSamplerOptions options;
  EXPECT_NO_THROW(options.Check());
  options.patch_size_px = 7;
  try {
    options.Check();
    FAIL() << "patch size 7 accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("patch_size_px"), std::string::npos) << e.what();
  }
  for (const double support : {0.0, -2.0, std::numeric_limits<double>::quiet_NaN()}) {
    PatchSamplerOptions bad;
    bad.support_per_size = support;
    try {
      bad.Check();
      FAIL() << "support " << support << " accepted";
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find("support_per_size"), std::string::npos) << e.what();
    }
  }
  PatchSamplerOptions bad;
  bad.patch_size_px = 4;
  EXPECT_THROW(PatchSampler(testing::TexturedImage(64, 64), bad), ConfigError);
}

TEST(PatchSampler, NoKeypointsGiveAnEmptyMatrixOfPatchRows) {
  const PatchSampler sampler(testing::TexturedImage(64, 48), PatchSamplerOptions());
  const cv::Mat patches = sampler.Sample({});
  EXPECT_EQ(patches.rows, 0);
  EXPECT_EQ(patches.cols, 32 * 32);
  EXPECT_EQ(patches.type(), CV_8U);
}

TEST(PatchSampler, SmallKeypointsMatchTheDefinitionAtLevelZero) {
  const cv::Mat image = testing::TexturedImage(320, 240, 3);
  const PatchSampler sampler(image, PatchSamplerOptions());
  // size 5: one patch pixel is 30/32 image pixels, level 0.
  const std::vector<cv::KeyPoint> keypoints = {cv::KeyPoint(100.3f, 80.7f, 5.0f, 0.0f),
                                               cv::KeyPoint(200.0f, 150.0f, 5.0f, 37.0f),
                                               cv::KeyPoint(160.5f, 60.25f, 4.0f, 250.0f)};
  const cv::Mat patches = sampler.Sample(keypoints);
  ASSERT_EQ(patches.rows, 3);
  for (int k = 0; k < 3; ++k) {
    EXPECT_LT(MeanAbsDiff(patches.row(k), ReferencePatch(image, keypoints[k], 32, 6.0)), 0.6)
        << "keypoint " << k;
  }
  // The order of the rows is the keypoints' order.
  EXPECT_GT(MeanAbsDiff(patches.row(0), patches.row(1)), 5.0);
}

TEST(PatchSampler, BorderIsReplicated) {
  // A linear ramp 3x + 2y: bilinear sampling reproduces it exactly inside the
  // image, and the clamped ramp outside.
  cv::Mat image(40, 40, CV_8U);
  for (int y = 0; y < 40; ++y) {
    for (int x = 0; x < 40; ++x) image.at<uint8_t>(y, x) = static_cast<uint8_t>(3 * x + 2 * y);
  }
  PatchSamplerOptions options;
  options.support_per_size = 32.0;  // size 1: one patch pixel per image pixel
  const PatchSampler sampler(image, options);
  const cv::KeyPoint corner(1.0f, 37.0f, 1.0f, 0.0f);
  const cv::Mat patch = sampler.Sample({corner}).reshape(1, 32);
  int outside = 0;
  for (int v = 0; v < 32; ++v) {
    for (int u = 0; u < 32; ++u) {
      const double x = std::clamp(1.0 + u - 15.5, 0.0, 39.0);
      const double y = std::clamp(37.0 + v - 15.5, 0.0, 39.0);
      outside += (x == 0.0 || y == 39.0) ? 1 : 0;
      EXPECT_NEAR(patch.at<uint8_t>(v, u), 3 * x + 2 * y, 1.0) << "u " << u << " v " << v;
    }
  }
  EXPECT_GT(outside, 32 * 32 / 2);  // most of the patch lies outside the image
}

TEST(PatchSampler, UprightIgnoresTheAngle) {
  const cv::Mat image = testing::TexturedImage(200, 200, 5);
  PatchSamplerOptions options;
  options.oriented = false;
  const PatchSampler sampler(image, options);
  const cv::Mat patches = sampler.Sample({cv::KeyPoint(100.0f, 100.0f, 6.0f, 0.0f),
                                          cv::KeyPoint(100.0f, 100.0f, 6.0f, 90.0f)});
  EXPECT_EQ(MeanAbsDiff(patches.row(0), patches.row(1)), 0.0);
  const PatchSampler oriented(image, PatchSamplerOptions());
  const cv::Mat turned = oriented.Sample({cv::KeyPoint(100.0f, 100.0f, 6.0f, 0.0f),
                                          cv::KeyPoint(100.0f, 100.0f, 6.0f, 90.0f)});
  EXPECT_GT(MeanAbsDiff(turned.row(0), turned.row(1)), 5.0);
}

// The signed difference a - b of two angles in degrees, in (-180, 180].
double AngleDiffDeg(double a, double b) {
  double d = std::fmod(a - b, 360.0);
  if (d <= -180.0) d += 360.0;
  if (d > 180.0) d -= 360.0;
  return d;
}

// cv::SIFT's KeyPoint::angle on an image turned by +theta (cv::getRotationMatrix2D,
// counter-clockwise on screen) is the original angle minus theta: the
// convention the sampler's transformed keypoints below use.
TEST(PatchSampler, SiftAnglesTurnByMinusTheImageRotation) {
  const cv::Mat image = testing::TexturedImage(480, 480, 7);
  const double theta = 40.0;
  const cv::Mat affine = cv::getRotationMatrix2D(cv::Point2f(239.5f, 239.5f), theta, 1.0);
  cv::Mat turned;
  cv::warpAffine(image, turned, affine, image.size(), cv::INTER_LINEAR, cv::BORDER_REFLECT_101);
  const cv::Ptr<cv::SIFT> sift = cv::SIFT::create(500);
  std::vector<cv::KeyPoint> before, after;
  sift->detect(image, before);
  sift->detect(turned, after);
  std::vector<double> minus, plus;
  for (const cv::KeyPoint& kp : before) {
    const cv::Point2f moved = Apply(affine, kp.pt);
    if (cv::norm(moved - cv::Point2f(239.5f, 239.5f)) > 180.0) continue;  // stays inside
    for (const cv::KeyPoint& other : after) {
      if (cv::norm(other.pt - moved) < 1.0 && std::abs(other.size - kp.size) < 0.1 * kp.size) {
        minus.push_back(std::abs(AngleDiffDeg(other.angle, kp.angle - theta)));
        plus.push_back(std::abs(AngleDiffDeg(other.angle, kp.angle + theta)));
        break;
      }
    }
  }
  ASSERT_GT(minus.size(), 30u);
  std::sort(minus.begin(), minus.end());
  std::sort(plus.begin(), plus.end());
  EXPECT_LT(minus[minus.size() / 2], 5.0);
  EXPECT_GT(plus[plus.size() / 2], 60.0);
}

struct Similarity {
  double theta_deg;
  double scale;
};

// Patches at a keypoint and at its image under a similarity about a point
// (size scaled, angle turned by -theta as cv::SIFT assigns it) agree.
TEST(PatchSampler, PatchesAgreeUnderAnAnalyticRotationAndScale) {
  const cv::Mat image = testing::TexturedImage(640, 480, 11);
  const PatchSampler sampler(image, PatchSamplerOptions());
  const cv::Point2f pivot(320.0f, 240.0f);
  const std::vector<cv::KeyPoint> keypoints = {cv::KeyPoint(pivot, 6.0f, 20.0f),
                                               cv::KeyPoint(300.0f, 230.0f, 9.0f, 300.0f),
                                               cv::KeyPoint(340.5f, 255.5f, 8.0f, 135.0f)};
  const cv::Mat reference = sampler.Sample(keypoints);
  for (const Similarity& sim : {Similarity{30.0, 1.0}, Similarity{-75.0, 1.5},
                                Similarity{90.0, 0.8}, Similarity{150.0, 2.5}}) {
    const cv::Mat affine = cv::getRotationMatrix2D(pivot, sim.theta_deg, sim.scale);
    cv::Mat warped;
    cv::warpAffine(image, warped, affine, image.size(), cv::INTER_LINEAR, cv::BORDER_REFLECT_101);
    std::vector<cv::KeyPoint> moved, wrong_sign;
    for (const cv::KeyPoint& kp : keypoints) {
      const float size = static_cast<float>(kp.size * sim.scale);
      moved.emplace_back(Apply(affine, kp.pt), size,
                         static_cast<float>(std::fmod(kp.angle - sim.theta_deg + 720.0, 360.0)));
      wrong_sign.emplace_back(Apply(affine, kp.pt), size,
                              static_cast<float>(std::fmod(kp.angle + sim.theta_deg + 720.0, 360.0)));
    }
    const PatchSampler warped_sampler(warped, PatchSamplerOptions());
    const cv::Mat patches = warped_sampler.Sample(moved);
    const cv::Mat wrong = warped_sampler.Sample(wrong_sign);
    for (size_t k = 0; k < keypoints.size(); ++k) {
      const int row = static_cast<int>(k);
      const double agree = MeanAbsDiff(patches.row(row), reference.row(row));
      EXPECT_LT(agree, 8.0) << "theta " << sim.theta_deg << " scale " << sim.scale << " keypoint " << k;
      EXPECT_GT(MeanAbsDiff(wrong.row(row), reference.row(row)), 3.0 * agree + 2.0)
          << "theta " << sim.theta_deg << " scale " << sim.scale << " keypoint " << k;
    }
  }
}

// A keypoint much larger than the patch is sampled from a coarser pyramid
// level: its patch is close to the blurred image's, not to the aliased samples
// of the full-resolution image.
TEST(PatchSampler, LargeKeypointsAreNotAliased) {
  const cv::Mat image = testing::AddNoise(testing::TexturedImage(640, 480, 13), 40.0, 2);
  const cv::KeyPoint large(320.0f, 240.0f, 40.0f, 30.0f);  // one patch pixel: 7.5 image pixels
  const PatchSampler sampler(image, PatchSamplerOptions());
  const cv::Mat patch = sampler.Sample({large});
  cv::Mat blurred;
  cv::GaussianBlur(image, blurred, cv::Size(0, 0), 3.0);
  const cv::Mat smooth = ReferencePatch(blurred, large, 32, 6.0);
  const cv::Mat aliased = ReferencePatch(image, large, 32, 6.0);
  const double sampled_error = MeanAbsDiff(patch, smooth);
  EXPECT_LT(sampled_error, 8.0);
  EXPECT_LT(sampled_error, 0.4 * MeanAbsDiff(aliased, smooth));
}

}  // namespace
}  // namespace duskmap
