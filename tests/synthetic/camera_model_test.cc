#include "slam/synthetic/sensor/camera_model.h"

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

// The image of `scene` from a camera with options `a` and one with `b`, each
// settled on the scene first.
std::pair<cv::Mat, cv::Mat> CaptureSettled(const CameraModelOptions& a, const CameraModelOptions& b,
                                           const cv::Mat& scene, uint64_t seed) {
  CameraModel first(a, seed), second(b, seed);
  first.Settle(scene, 20);
  second.Settle(scene, 20);
  return {first.Capture(scene), second.Capture(scene)};
}

TEST(CameraModel, AutoExposureKeepsBrightnessNearTargetExceptAfterASuddenChange) {
  const CameraModelOptions options = SmallOptions();
  CameraModel camera(options, 1);
  const cv::Mat dim = Scene(40.0f, 1), bright = Scene(320.0f, 2);
  std::vector<double> brightness;
  for (int i = 0; i < 10; ++i) brightness.push_back(MeanBrightness(camera.Capture(dim)));
  for (int i = 0; i < 10; ++i) brightness.push_back(MeanBrightness(camera.Capture(bright)));
  // Converged on the dim scene.
  for (int i = 6; i < 10; ++i) EXPECT_NEAR(brightness[i], options.exposure.target, 0.06) << "frame " << i;
  // The first frame after the 8x jump is overexposed: the lag.
  EXPECT_GT(brightness[10], options.exposure.target + 0.2);
  // Then it converges again within a few frames.
  for (int i = 16; i < 20; ++i) EXPECT_NEAR(brightness[i], options.exposure.target, 0.06) << "frame " << i;
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

// Mean squared horizontal gradient of the green channel (sharpness along x;
// unlike the mean absolute gradient it drops when edges are smeared).
double HorizontalDetail(const cv::Mat& bgr) {
  cv::Mat g, dx;
  cv::extractChannel(bgr, g, 1);
  g.convertTo(g, CV_32F);
  cv::Sobel(g, dx, CV_32F, 1, 0);
  return cv::mean(dx.mul(dx))[0];
}

TEST(CameraModel, TurningSmearsLongExposuresButNotShortOnes) {
  CameraModelOptions options = SmallOptions();
  options.exposure.motion_blur_scale = 1.0;
  options.noise.photons_at_white = 1e9;  // no noise: compare detail only
  options.noise.read_noise = 0.0;
  // Vertical stripes 8 px wide: horizontal motion blurs them, vertical does not.
  auto stripes = [](float nits) {
    cv::Mat r(120, 160, CV_32FC3);
    for (int c = 0; c < 160; ++c) r.col(c).setTo(cv::Scalar::all((c / 8) % 2 ? nits : 0.2 * nits));
    return r;
  };
  const cv::Mat dim = stripes(2.0f), bright = stripes(4000.0f);
  const cv::Vec2d turning(200.0, 0.0), tilting(0.0, 200.0);  // px/s
  CameraModel night(options, 1), day(options, 1);
  night.Settle(dim, 20);
  day.Settle(bright, 20);
  ASSERT_NEAR(night.state().exposure_time_s, options.exposure.max_time_s, 1e-9);  // 33 ms: 6.6 px of motion
  ASSERT_LT(day.state().exposure_time_s, 0.002);                             // < 0.4 px of motion
  const double night_still = HorizontalDetail(night.Capture(dim));
  const double night_turning = HorizontalDetail(night.Capture(dim, turning));
  const double night_tilting = HorizontalDetail(night.Capture(dim, tilting));
  EXPECT_LT(night_turning, 0.6 * night_still);
  EXPECT_NEAR(night_tilting, night_still, 0.05 * night_still);
  const double day_still = HorizontalDetail(day.Capture(bright));
  const double day_turning = HorizontalDetail(day.Capture(bright, turning));
  EXPECT_NEAR(day_turning, day_still, 0.05 * day_still);
}

TEST(CameraModel, SharpeningSteepensEdgesAndItsThresholdSparesFlatNoise) {
  // Vertical stripes 8 px wide, no sensor noise: the unsharp mask overshoots at each edge.
  CameraModelOptions clean = SmallOptions();
  clean.noise.photons_at_white = 1e9;
  clean.noise.read_noise = 0.0;
  cv::Mat stripes(120, 160, CV_32FC3);
  for (int c = 0; c < 160; ++c) stripes.col(c).setTo(cv::Scalar::all((c / 8) % 2 ? 60.0 : 20.0));
  CameraModelOptions sharp = clean;
  sharp.image_processor.sharpen_amount = 1.0;
  const auto [plain, sharpened] = CaptureSettled(clean, sharp, stripes, 1);
  cv::Mat plain_green, sharp_green;
  cv::extractChannel(plain, plain_green, 1);
  cv::extractChannel(sharpened, sharp_green, 1);
  double plain_min, plain_max, sharp_min, sharp_max;
  cv::minMaxLoc(plain_green, &plain_min, &plain_max);
  cv::minMaxLoc(sharp_green, &sharp_min, &sharp_max);
  EXPECT_GE(sharp_max, plain_max + 2);  // overshoot on the bright side of each edge
  EXPECT_LE(sharp_min, plain_min - 4);  // and undershoot on the dark side
  EXPECT_GT(HorizontalDetail(sharpened), 1.3 * HorizontalDetail(plain));
  // Grey stays grey: the same offset on every channel.
  const cv::Vec3b px = sharpened.at<cv::Vec3b>(60, 8);
  EXPECT_EQ(px[0], px[1]);
  EXPECT_EQ(px[1], px[2]);

  // A flat dim scene at high gain (noise std about 15 grey levels): sharpening amplifies the
  // noise, unless it lies under the threshold.
  const cv::Mat flat(120, 160, CV_32FC3, cv::Scalar(2, 2, 2));
  CameraModelOptions noisy = SmallOptions();
  CameraModelOptions noisy_sharp = noisy;
  noisy_sharp.image_processor.sharpen_amount = 1.0;
  CameraModelOptions noisy_cored = noisy_sharp;
  noisy_cored.image_processor.sharpen_threshold_levels = 32.0;
  CameraModel a(noisy, 5), b(noisy_sharp, 5), c(noisy_cored, 5);
  for (CameraModel* camera : {&a, &b, &c}) camera->Settle(flat, 20);
  cv::Scalar mean, std_plain, std_sharp, std_cored;
  cv::meanStdDev(a.Capture(flat), mean, std_plain);
  cv::meanStdDev(b.Capture(flat), mean, std_sharp);
  cv::meanStdDev(c.Capture(flat), mean, std_cored);
  EXPECT_GT(std_sharp[1], 1.3 * std_plain[1]);
  EXPECT_LT(std_cored[1], 1.1 * std_plain[1]);
}

TEST(CameraModel, NoiseReductionFollowsTheGainAndKeepsEdges) {
  // The model's mid-grey noise: one channel's std, in grey levels, grows with the gain.
  const CameraModelOptions options = SmallOptions();
  CameraModel day(options, 3), night(options, 3);
  day.Settle(cv::Mat(120, 160, CV_32FC3, cv::Scalar(60, 60, 60)), 20);
  const cv::Mat flat(120, 160, CV_32FC3, cv::Scalar(2, 2, 2));
  night.Settle(flat, 20);
  EXPECT_GT(night.MidGreyNoiseLevels(), 6.0 * day.MidGreyNoiseLevels());
  // A dim scene at high gain, half of it 4x brighter: the filter removes most of the flat
  // halves' noise and keeps the step between them.
  cv::Mat step = flat.clone();
  step.colRange(80, 160).setTo(cv::Scalar(8, 8, 8));
  CameraModelOptions reduced = options;
  reduced.image_processor.noise_reduction = 1.5;
  const auto [plain, denoised] = CaptureSettled(options, reduced, step, 5);
  cv::Scalar plain_mean, plain_std, reduced_mean, reduced_std;
  const cv::Rect dark_half(10, 10, 60, 100), bright_half(90, 10, 60, 100);
  cv::meanStdDev(plain(dark_half), plain_mean, plain_std);
  cv::meanStdDev(denoised(dark_half), reduced_mean, reduced_std);
  EXPECT_LT(reduced_std[1], 0.5 * plain_std[1]);
  EXPECT_NEAR(reduced_mean[1], plain_mean[1], 2.0);
  const double plain_step = cv::mean(plain(bright_half))[1] - plain_mean[1];
  const double reduced_step = cv::mean(denoised(bright_half))[1] - reduced_mean[1];
  EXPECT_GT(plain_step, 40.0);
  EXPECT_NEAR(reduced_step, plain_step, 0.05 * plain_step);
  // Across the step itself the image stays sharp: the column just right of it keeps its level.
  EXPECT_NEAR(cv::mean(denoised.col(81))[1], cv::mean(denoised(bright_half))[1], 0.1 * plain_step);
}

TEST(CameraModelOptions, CheckNamesTheField) {
  CameraModelOptions o;
  o.exposure.speed = 0.0;
  try {
    o.Check();
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("camera.exposure.speed"), std::string::npos);
  }
  CameraModelOptions nr;
  nr.image_processor.noise_reduction = -1.0;
  EXPECT_THROW(nr.Check(), ConfigError);
  nr.image_processor.noise_reduction = 1.0;
  nr.image_processor.noise_reduction_sigma_px = 0.0;
  EXPECT_THROW(nr.Check(), ConfigError);
}

}  // namespace
}  // namespace duskmap
