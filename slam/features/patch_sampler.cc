#include "slam/features/patch_sampler.h"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

#include "slam/core/check.h"

namespace duskmap {
namespace {

constexpr double kPi = 3.14159265358979323846;

// The pyramid level at which one patch pixel (`step_px` level-0 pixels) spans
// one to two level pixels; level 0 when a patch pixel is under one pixel.
int LevelFor(double step_px, int levels) {
  const int level = step_px < 2.0 ? 0 : static_cast<int>(std::floor(std::log2(step_px)));
  return std::min(level, levels - 1);
}

}  // namespace

void PatchSamplerOptions::Check() const {
  SLAM_THROW_IF_NOT(ConfigError, patch_size_px >= 8 && patch_size_px <= 256)
      << "patch_size_px: must be in [8, 256], got " << patch_size_px;
  SLAM_THROW_IF_NOT(ConfigError, std::isfinite(support_per_size) && support_per_size > 0.0)
      << "support_per_size: must be a positive number, got " << support_per_size;
}

PatchSampler::PatchSampler(const cv::Mat& gray, const PatchSamplerOptions& options)
    : options_(options) {
  options_.Check();
  SLAM_CHECK_MSG(!gray.empty() && gray.type() == CV_8UC1, "PatchSampler needs an 8-bit gray image");
  pyramid_.push_back(gray);
  while (pyramid_.back().rows >= 2 && pyramid_.back().cols >= 2) {
    cv::Mat next;
    cv::pyrDown(pyramid_.back(), next);
    pyramid_.push_back(next);
  }
}

cv::Mat PatchSampler::Sample(const std::vector<cv::KeyPoint>& keypoints) const {
  const int p = options_.patch_size_px;
  cv::Mat patches(static_cast<int>(keypoints.size()), p * p, CV_8U);
  const double centre = 0.5 * (p - 1);
  for (size_t k = 0; k < keypoints.size(); ++k) {
    const cv::KeyPoint& kp = keypoints[k];
    // One patch pixel in level-0 pixels, and the level that samples it unaliased.
    const double step_px = options_.support_per_size * std::max(kp.size, 1e-3f) / p;
    const int level = LevelFor(step_px, static_cast<int>(pyramid_.size()));
    const double scale = std::ldexp(1.0, -level);  // level pixels per level-0 pixel
    const double step = step_px * scale;
    // KeyPoint::angle (degrees) turns image +x towards image +y (y down), so
    // the patch's +x axis is (cos, sin) and its +y axis (-sin, cos) in the image.
    const double angle = options_.oriented && kp.angle >= 0.0f ? kp.angle * kPi / 180.0 : 0.0;
    const double c = std::cos(angle) * step, s = std::sin(angle) * step;
    // Level coordinates of a level-0 point: (x + 0.5) * scale - 0.5 (cv::pyrDown's grid).
    const double cx = (kp.pt.x + 0.5) * scale - 0.5, cy = (kp.pt.y + 0.5) * scale - 0.5;
    // Patch (u, v) -> level (x, y): the inverse map of cv::warpAffine.
    const cv::Matx23d patch_to_level(c, -s, cx - c * centre + s * centre,  //
                                     s, c, cy - s * centre - c * centre);
    cv::Mat patch(p, p, CV_8U, patches.ptr(static_cast<int>(k)));
    cv::warpAffine(pyramid_[level], patch, cv::Mat(patch_to_level), patch.size(),
                   cv::INTER_LINEAR | cv::WARP_INVERSE_MAP, cv::BORDER_REPLICATE);
  }
  return patches;
}

}  // namespace duskmap
