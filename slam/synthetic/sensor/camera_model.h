// The colour camera: turns a radiance image (nits) into an 8-bit BGR image
// the way a consumer RGB-D camera does, with state carried across frames:
// auto-exposure with lag (metering the mean brightness of the previous
// frame), grey-world auto white balance with lag and partial strength, optics
// blur, shot and read noise that grow with analogue gain, a tone curve with
// clipping and 8-bit quantisation, then the image processor's noise
// reduction (an edge-preserving filter whose strength follows the noise the
// gain brings) and sharpening (an unsharp mask of the luma with a noise
// threshold), as phone cameras apply them. Seeded: the same inputs give the
// same bytes.
#pragma once

#include <cstdint>

#include <opencv2/core.hpp>

#include "slam/core/camera.h"
#include "slam/synthetic/sensor/sensor_noise.h"

namespace duskmap {

// Auto-exposure: how the camera meters and what exposure it may choose.
struct CameraExposureOptions {
  double target = 0.42;       // target mean brightness of the output, in [0, 1]
  double speed = 0.55;        // fraction of the log exposure error corrected per frame
  double min_time_s = 1e-4;   // shortest exposure time, seconds
  double max_time_s = 0.033;  // longest exposure time, seconds
  double max_gain = 16.0;     // largest analogue gain (1 = base ISO)
  double sensitivity = 0.135; // linear signal per nit-second at gain 1 (1 = white)
  double motion_blur_scale = 0.0;  // motion blur = image velocity x exposure time x this; 0 = off
};

// Grey-world auto white balance.
struct WhiteBalanceOptions {
  double speed = 0.4;      // fraction of the log white-balance error corrected per frame
  double strength = 0.75;  // fraction of the grey-world correction applied
};

// The sensor's noise, at gain 1 (both grow with the gain).
struct CameraNoiseOptions {
  double photons_at_white = 8000;  // shot noise: photo-electrons at full scale
  double read_noise = 0.002;       // read noise std, fraction of full scale
};

// The image processor: the tone curve, then noise reduction and sharpening
// of the 8-bit output.
struct ImageProcessorOptions {
  double gamma = 2.2;          // display gamma of the tone curve
  double tone_contrast = 0.12; // S-curve strength added to the gamma curve, [0, 0.5]
  // Noise reduction, before sharpening: a bilateral filter (spatial sigma
  // noise_reduction_sigma_px) whose range sigma is noise_reduction x the noise a mid-grey
  // pixel carries at the frame's gain, summed over the three channels (the filter's colour
  // distance is the sum of the channels' absolute differences). 0 = off.
  double noise_reduction = 0.0;           // [0, 5]
  double noise_reduction_sigma_px = 1.5;  // (0, 5], pixels
  // Sharpening: luma += amount x coring(luma - Gaussian(luma, sigma)), where coring shrinks
  // each detail value towards 0 by threshold grey levels (noise below it is not
  // amplified). 0 = off.
  double sharpen_amount = 0.0;            // [0, 3]
  double sharpen_sigma_px = 1.0;          // (0, 5], pixels
  double sharpen_threshold_levels = 0.0;  // [0, 64], grey levels of 255
};

// The lens and image size, then each stage's options (JSON: the same nesting,
// generator_config_json.h). Every stage's extras default to off: the
// generator's models (generator_models.h) turn them on.
struct CameraModelOptions {
  int width = 640;              // pixels
  int height = 480;             // pixels
  double fx = 525.0;            // focal length, pixels
  double fy = 525.0;            // focal length, pixels
  double blur_sigma_px = 0.6;   // optics blur, pixels
  CameraExposureOptions exposure;
  WhiteBalanceOptions white_balance;
  CameraNoiseOptions noise;
  ImageProcessorOptions image_processor;

  PinholeCamera Intrinsics() const;
  void Check() const;
};

struct CameraState {
  double exposure = 0.01;  // exposure time x gain x sensitivity (signal per nit)
  cv::Vec3d wb_gains = cv::Vec3d(1, 1, 1);
  double exposure_time_s = 0.01;
  double gain = 1.0;
  double last_mean_brightness = 0.0;  // mean output brightness of the last frame, [0, 1]
};

class CameraModel {
 public:
  CameraModel(const CameraModelOptions& options, uint64_t seed);

  // Produces the image of this radiance, then updates exposure and white
  // balance from it (they act from the next frame on: the lag). The image
  // moves at image_velocity_px_per_s (x, y) during the exposure: a box blur
  // of |velocity| x exposure time pixels along each axis (long night
  // exposures smear while the camera turns; daylight ones stay sharp).
  cv::Mat Capture(const cv::Mat& radiance_bgr, const cv::Vec2d& image_velocity_px_per_s = cv::Vec2d(0, 0));
  // Meters the radiance `iterations` times without producing an image, as a
  // running camera does before the first recorded frame.
  void Settle(const cv::Mat& radiance_bgr, int iterations);

  const CameraState& state() const { return state_; }
  // The tone curve: linear [0, 1] -> output [0, 1].
  double Tone(double linear) const;
  // Noise std of one channel of a mid-grey pixel (linear 0.18) in output
  // grey levels of 255, at the current gain: shot and read noise through the
  // tone curve's slope.
  double MidGreyNoiseLevels() const;

 private:
  void Meter(const cv::Mat& radiance_bgr);
  void SetExposure(double exposure);
  void Sharpen(cv::Mat* bgr);
  void ReduceNoise(cv::Mat* bgr);

  CameraModelOptions options_;
  CameraState state_;
  SensorNoise noise_;
  std::vector<uint8_t> tone_lut_;  // 4096 entries over [0, 1]
  cv::Mat blurred_;                // scratch: blurred radiance, reused across frames
  cv::Mat smeared_;                // scratch: motion-blurred radiance
  std::vector<float> noise_row_;   // scratch: one row of normal samples
  cv::Mat luma_, luma_blurred_;    // scratch: sharpening
  cv::Mat denoised_;               // scratch: noise reduction
};

}  // namespace duskmap
