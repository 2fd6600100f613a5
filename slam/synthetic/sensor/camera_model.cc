#include "slam/synthetic/sensor/camera_model.h"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

#include "slam/core/check.h"

namespace duskmap {
namespace {
constexpr int kLutSize = 4096;
constexpr int kMeterStride = 4;  // metering samples every 4th pixel in x and y
}  // namespace

PinholeCamera CameraModelOptions::Intrinsics() const {
  PinholeCamera c;
  c.width = width;
  c.height = height;
  c.fx = fx;
  c.fy = fy;
  c.cx = (width - 1) / 2.0;
  c.cy = (height - 1) / 2.0;
  return c;
}

void CameraModelOptions::Check() const {
  SLAM_THROW_IF_NOT(ConfigError, width >= 16 && width <= 4096) << "camera.width must be in [16, 4096], got " << width;
  SLAM_THROW_IF_NOT(ConfigError, height >= 16 && height <= 4096) << "camera.height must be in [16, 4096], got " << height;
  // A focal length beyond 100x the image size is a field of view under 0.6 degrees: a typo.
  SLAM_THROW_IF_NOT(ConfigError, fx > 0 && fy > 0 && fx <= 100.0 * width && fy <= 100.0 * height)
      << "camera.fx and camera.fy must be in (0, 100 x the image width/height], got " << fx
      << " and " << fy;
  SLAM_THROW_IF_NOT(ConfigError, blur_sigma_px >= 0 && blur_sigma_px <= 5) << "camera.blur_sigma_px must be in [0, 5]";
  const CameraExposureOptions& e = exposure;
  SLAM_THROW_IF_NOT(ConfigError, e.target > 0.05 && e.target < 0.95)
      << "camera.exposure.target must be in (0.05, 0.95), got " << e.target;
  SLAM_THROW_IF_NOT(ConfigError, e.speed > 0 && e.speed <= 1) << "camera.exposure.speed must be in (0, 1], got " << e.speed;
  SLAM_THROW_IF_NOT(ConfigError, e.min_time_s > 0 && e.max_time_s > e.min_time_s)
      << "camera.exposure.min_time_s/max_time_s must satisfy 0 < min < max";
  SLAM_THROW_IF_NOT(ConfigError, e.max_gain >= 1) << "camera.exposure.max_gain must be >= 1, got " << e.max_gain;
  SLAM_THROW_IF_NOT(ConfigError, e.sensitivity > 0) << "camera.exposure.sensitivity must be > 0";
  SLAM_THROW_IF_NOT(ConfigError, e.motion_blur_scale >= 0 && e.motion_blur_scale <= 4)
      << "camera.exposure.motion_blur_scale must be in [0, 4], got " << e.motion_blur_scale;
  const WhiteBalanceOptions& wb = white_balance;
  SLAM_THROW_IF_NOT(ConfigError, wb.speed > 0 && wb.speed <= 1)
      << "camera.white_balance.speed must be in (0, 1], got " << wb.speed;
  SLAM_THROW_IF_NOT(ConfigError, wb.strength >= 0 && wb.strength <= 1)
      << "camera.white_balance.strength must be in [0, 1], got " << wb.strength;
  SLAM_THROW_IF_NOT(ConfigError, noise.photons_at_white > 0) << "camera.noise.photons_at_white must be > 0";
  SLAM_THROW_IF_NOT(ConfigError, noise.read_noise >= 0) << "camera.noise.read_noise must be >= 0";
  const ImageProcessorOptions& ip = image_processor;
  SLAM_THROW_IF_NOT(ConfigError, ip.gamma >= 1 && ip.gamma <= 3)
      << "camera.image_processor.gamma must be in [1, 3], got " << ip.gamma;
  SLAM_THROW_IF_NOT(ConfigError, ip.tone_contrast >= 0 && ip.tone_contrast <= 0.5)
      << "camera.image_processor.tone_contrast must be in [0, 0.5]";
  SLAM_THROW_IF_NOT(ConfigError, ip.sharpen_amount >= 0 && ip.sharpen_amount <= 3)
      << "camera.image_processor.sharpen_amount must be in [0, 3], got " << ip.sharpen_amount;
  SLAM_THROW_IF_NOT(ConfigError, ip.sharpen_sigma_px > 0 && ip.sharpen_sigma_px <= 5)
      << "camera.image_processor.sharpen_sigma_px must be in (0, 5], got " << ip.sharpen_sigma_px;
  SLAM_THROW_IF_NOT(ConfigError, ip.sharpen_threshold_levels >= 0 && ip.sharpen_threshold_levels <= 64)
      << "camera.image_processor.sharpen_threshold_levels must be in [0, 64], got " << ip.sharpen_threshold_levels;
  SLAM_THROW_IF_NOT(ConfigError, ip.noise_reduction >= 0 && ip.noise_reduction <= 5)
      << "camera.image_processor.noise_reduction must be in [0, 5], got " << ip.noise_reduction;
  SLAM_THROW_IF_NOT(ConfigError, ip.noise_reduction_sigma_px > 0 && ip.noise_reduction_sigma_px <= 5)
      << "camera.image_processor.noise_reduction_sigma_px must be in (0, 5], got " << ip.noise_reduction_sigma_px;
}

CameraModel::CameraModel(const CameraModelOptions& options, uint64_t seed)
    : options_(options), noise_(seed) {
  options_.Check();
  tone_lut_.resize(kLutSize);
  for (int i = 0; i < kLutSize; ++i) {
    tone_lut_[i] = cv::saturate_cast<uint8_t>(Tone(i / (kLutSize - 1.0)) * 255.0);
  }
  SetExposure(options_.exposure.sensitivity * options_.exposure.max_time_s);
}

double CameraModel::Tone(double linear) const {
  const double g = std::pow(std::clamp(linear, 0.0, 1.0), 1.0 / options_.image_processor.gamma);
  // Smooth S-curve around mid grey: g + c * g (1 - g) (2 g - 1).
  return std::clamp(g + options_.image_processor.tone_contrast * g * (1 - g) * (2 * g - 1) * 2.0, 0.0, 1.0);
}

double CameraModel::MidGreyNoiseLevels() const {
  constexpr double kMidGrey = 0.18, kStep = 0.01;
  const double shot = state_.gain / options_.noise.photons_at_white;
  const double read = options_.noise.read_noise * state_.gain;
  const double std_linear = std::sqrt(shot * kMidGrey + read * read);
  const double slope = (Tone(kMidGrey + kStep) - Tone(kMidGrey - kStep)) / (2.0 * kStep);
  return std_linear * slope * 255.0;
}

void CameraModel::SetExposure(double exposure) {
  const double lo = options_.exposure.sensitivity * options_.exposure.min_time_s;
  const double hi = options_.exposure.sensitivity * options_.exposure.max_time_s * options_.exposure.max_gain;
  state_.exposure = std::clamp(exposure, lo, hi);
  const double time_s = state_.exposure / options_.exposure.sensitivity;
  state_.exposure_time_s = std::min(time_s, options_.exposure.max_time_s);
  state_.gain = std::max(1.0, time_s / options_.exposure.max_time_s);
}

void CameraModel::Meter(const cv::Mat& radiance) {
  double sum_y = 0.0;
  cv::Vec3d sum_c(0, 0, 0);
  int n = 0, n_c = 0;
  for (int r = kMeterStride / 2; r < radiance.rows; r += kMeterStride) {
    const cv::Vec3f* row = radiance.ptr<cv::Vec3f>(r);
    for (int c = kMeterStride / 2; c < radiance.cols; c += kMeterStride) {
      cv::Vec3d v(row[c][0] * state_.wb_gains[0], row[c][1] * state_.wb_gains[1], row[c][2] * state_.wb_gains[2]);
      v *= state_.exposure;
      const double y = 0.0722 * v[0] + 0.7152 * v[1] + 0.2126 * v[2];
      sum_y += Tone(y);
      ++n;
      if (v[0] < 0.98 && v[1] < 0.98 && v[2] < 0.98 && y > 0.002) {
        sum_c += cv::Vec3d(row[c][0], row[c][1], row[c][2]);
        ++n_c;
      }
    }
  }
  const double mean = n > 0 ? sum_y / n : options_.exposure.target;
  state_.last_mean_brightness = mean;
  // Output brightness is roughly linear^(1/gamma): correct in the linear domain.
  const double ratio = std::pow(options_.exposure.target / std::max(mean, 1e-3), options_.image_processor.gamma);
  SetExposure(state_.exposure * std::exp(options_.exposure.speed * std::log(ratio)));
  if (n_c > 16 && sum_c[0] > 0 && sum_c[1] > 0 && sum_c[2] > 0) {
    for (int k = 0; k < 3; ++k) {
      const double target = std::clamp(std::pow(sum_c[1] / sum_c[k], options_.white_balance.strength), 0.4, 3.0);
      state_.wb_gains[k] = std::exp(std::log(state_.wb_gains[k]) +
                                    options_.white_balance.speed * (std::log(target) - std::log(state_.wb_gains[k])));
    }
  }
}

void CameraModel::Settle(const cv::Mat& radiance, int iterations) {
  for (int i = 0; i < iterations; ++i) Meter(radiance);
}

cv::Mat CameraModel::Capture(const cv::Mat& radiance, const cv::Vec2d& image_velocity_px_per_s) {
  SLAM_CHECK(radiance.type() == CV_32FC3);
  // Blur is linear, so blurring the radiance and scaling afterwards equals
  // scaling then blurring; the scale is folded into the per-pixel loop.
  const cv::Mat* linear = &radiance;
  // Motion blur: a box along x and y (separable, O(1) per pixel) whose
  // lengths are the image motion during the exposure.
  const double smear_s = state_.exposure_time_s * options_.exposure.motion_blur_scale;
  const int smear_x = std::min(64, static_cast<int>(std::lround(std::abs(image_velocity_px_per_s[0]) * smear_s)));
  const int smear_y = std::min(64, static_cast<int>(std::lround(std::abs(image_velocity_px_per_s[1]) * smear_s)));
  if (smear_x >= 2 || smear_y >= 2) {
    cv::blur(radiance, smeared_, cv::Size(std::max(1, smear_x), std::max(1, smear_y)), cv::Point(-1, -1),
             cv::BORDER_REFLECT);
    linear = &smeared_;
  }
  if (options_.blur_sigma_px > 0.0) {
    cv::GaussianBlur(*linear, blurred_, cv::Size(0, 0), options_.blur_sigma_px);
    linear = &blurred_;
  }
  const float scale[3] = {static_cast<float>(state_.exposure * state_.wb_gains[0]),
                          static_cast<float>(state_.exposure * state_.wb_gains[1]),
                          static_cast<float>(state_.exposure * state_.wb_gains[2])};
  const float shot = static_cast<float>(state_.gain / options_.noise.photons_at_white);
  const float read = static_cast<float>(options_.noise.read_noise * state_.gain);
  const float read2 = read * read;
  const float lut_scale = static_cast<float>(kLutSize - 1);
  const int values = linear->cols * 3;
  noise_row_.resize(values);
  cv::Mat out(linear->size(), CV_8UC3);
  for (int r = 0; r < linear->rows; ++r) {
    const float* in = linear->ptr<float>(r);
    float* nz = noise_row_.data();
    noise_.FillNormal(nz, values);
    uint8_t* o = out.ptr<uint8_t>(r);
    for (int i = 0; i < values; i += 3) {
      for (int k = 0; k < 3; ++k) {
        const float x = std::min(in[i + k] * scale[k], 1.0f);
        const float v = x + std::sqrt(shot * x + read2) * nz[i + k];
        const int index = static_cast<int>(std::clamp(v, 0.0f, 1.0f) * lut_scale + 0.5f);
        o[i + k] = tone_lut_[index];
      }
    }
  }
  if (options_.image_processor.noise_reduction > 0.0) ReduceNoise(&out);
  if (options_.image_processor.sharpen_amount > 0.0) Sharpen(&out);
  Meter(radiance);
  return out;
}

void CameraModel::ReduceNoise(cv::Mat* bgr) {
  const double range_sigma = options_.image_processor.noise_reduction * 3.0 * MidGreyNoiseLevels();
  const double space_sigma = options_.image_processor.noise_reduction_sigma_px;
  const int diameter = 2 * static_cast<int>(std::ceil(2.0 * space_sigma)) + 1;
  cv::bilateralFilter(*bgr, denoised_, diameter, range_sigma, space_sigma, cv::BORDER_REFLECT);
  std::swap(*bgr, denoised_);
}

void CameraModel::Sharpen(cv::Mat* bgr) {
  luma_.create(bgr->size(), CV_32F);
  for (int r = 0; r < bgr->rows; ++r) {
    const uint8_t* in = bgr->ptr<uint8_t>(r);
    float* y = luma_.ptr<float>(r);
    for (int c = 0; c < bgr->cols; ++c) {
      y[c] = 0.114f * in[3 * c] + 0.587f * in[3 * c + 1] + 0.299f * in[3 * c + 2];
    }
  }
  cv::GaussianBlur(luma_, luma_blurred_, cv::Size(0, 0), options_.image_processor.sharpen_sigma_px, 0.0, cv::BORDER_REFLECT);
  const float amount = static_cast<float>(options_.image_processor.sharpen_amount);
  const float threshold = static_cast<float>(options_.image_processor.sharpen_threshold_levels);
  for (int r = 0; r < bgr->rows; ++r) {
    uint8_t* io = bgr->ptr<uint8_t>(r);
    const float* y = luma_.ptr<float>(r);
    const float* yb = luma_blurred_.ptr<float>(r);
    for (int c = 0; c < bgr->cols; ++c) {
      const float detail = y[c] - yb[c];
      const float cored = std::copysign(std::max(std::abs(detail) - threshold, 0.0f), detail);
      // The same offset on the three channels changes luma only, not hue.
      const float delta = amount * cored;
      for (int k = 0; k < 3; ++k) io[3 * c + k] = cv::saturate_cast<uint8_t>(io[3 * c + k] + delta);
    }
  }
}

}  // namespace duskmap
