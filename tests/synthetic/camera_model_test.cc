#include "slam/synthetic/camera_model.h"

#include "slam/core/check.h"

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

namespace duskmap {
namespace {

CameraModelOptions SmallOptions() {
  CameraModelOptions o;
  o.width = 160;
  o.height = 120;
  return o;
}

cv::Mat Scene(float nits, uint64_t seed) {
  cv::Mat radiance(120, 160, CV_32FC3);
  cv::RNG rng(seed);
  rng.fill(radiance, cv::RNG::UNIFORM, 0.3 * nits, 1.7 * nits);
  return radiance;
}

double MeanBrightness(const cv::Mat& bgr) {
  cv::Mat gray;
  cv::cvtColor(bgr, gray, cv::COLOR_BGR2GRAY);
  return cv::mean(gray)[0] / 255.0;
}

TEST(CameraModel, AutoExposureKeepsBrightnessNearTargetExceptAfterASuddenChange) {
  const CameraModelOptions options = SmallOptions();
  CameraModel camera(options, 1);
  const cv::Mat dim = Scene(40.0f, 1), bright = Scene(320.0f, 2);
  std::vector<double> brightness;
  for (int i = 0; i < 10; ++i) brightness.push_back(MeanBrightness(camera.Capture(dim)));
  for (int i = 0; i < 10; ++i) brightness.push_back(MeanBrightness(camera.Capture(bright)));
  // Converged on the dim scene.
  for (int i = 6; i < 10; ++i) EXPECT_NEAR(brightness[i], options.ae_target, 0.06) << "frame " << i;
  // The first frame after the 8x jump is overexposed: the lag.
  EXPECT_GT(brightness[10], options.ae_target + 0.2);
  // Then it converges again within a few frames.
  for (int i = 16; i < 20; ++i) EXPECT_NEAR(brightness[i], options.ae_target, 0.06) << "frame " << i;
}

TEST(CameraModel, GainAndNoiseGrowInTheDark) {
  const CameraModelOptions options = SmallOptions();
  CameraModel day(options, 1), night(options, 1);
  const cv::Mat flat_day(120, 160, CV_32FC3, cv::Scalar(60, 60, 60));
  const cv::Mat flat_night(120, 160, CV_32FC3, cv::Scalar(2, 2, 2));
  day.Settle(flat_day, 20);
  night.Settle(flat_night, 20);
  cv::Scalar mean_day, std_day, mean_night, std_night;
  cv::meanStdDev(day.Capture(flat_day), mean_day, std_day);
  cv::meanStdDev(night.Capture(flat_night), mean_night, std_night);
  EXPECT_NEAR(day.state().gain, 1.0, 1e-9);
  EXPECT_GT(night.state().gain, 8.0);
  EXPECT_GT(std_night[1], 2.5 * std_day[1]);
}

TEST(CameraModel, WhiteBalanceReducesAWarmCast) {
  CameraModel camera(SmallOptions(), 3);
  const cv::Mat warm(120, 160, CV_32FC3, cv::Scalar(10, 20, 40));  // BGR: orange light
  camera.Settle(warm, 30);
  const cv::Scalar mean = cv::mean(camera.Capture(warm));
  // Red/blue ratio smaller than the scene's (4) but not fully neutral (partial strength).
  const double ratio = mean[2] / mean[0];
  EXPECT_GT(ratio, 1.05);
  EXPECT_LT(ratio, 2.5);
}

TEST(CameraModel, SameSeedSameBytes) {
  CameraModel a(SmallOptions(), 9), b(SmallOptions(), 9);
  const cv::Mat radiance = Scene(50.0f, 4);
  EXPECT_EQ(cv::norm(a.Capture(radiance), b.Capture(radiance), cv::NORM_INF), 0.0);
}

TEST(CameraModelOptions, CheckNamesTheField) {
  CameraModelOptions o;
  o.ae_speed = 0.0;
  try {
    o.Check();
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("camera.ae_speed"), std::string::npos);
  }
}

}  // namespace
}  // namespace duskmap
