#include "slam/features/brief.h"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

#include "slam/core/random.h"
#include "slam/features/corner_detectors.h"

namespace duskmap {

std::vector<std::array<int8_t, 4>> MakeBriefPattern(const BriefOptions& options) {
  options.Check();
  Rng rng(options.pattern_seed);
  const double sigma = options.patch_size_px / 5.0;
  const int limit = options.patch_size_px / 2 - 1;
  std::normal_distribution<double> gauss(0.0, sigma);
  auto draw = [&] {
    return static_cast<int8_t>(std::clamp(static_cast<int>(std::lround(gauss(rng))), -limit, limit));
  };
  std::vector<std::array<int8_t, 4>> pattern;
  pattern.reserve(options.bytes * 8);
  while (pattern.size() < static_cast<size_t>(options.bytes * 8)) {
    std::array<int8_t, 4> p = {draw(), draw(), draw(), draw()};
    if (p[0] == p[2] && p[1] == p[3]) continue;  // a point against itself carries no bit
    pattern.push_back(p);
  }
  return pattern;
}

cv::Mat DescribeBrief(const cv::Mat& smoothed, const std::vector<cv::KeyPoint>& keypoints,
                      const std::vector<std::array<int8_t, 4>>& pattern) {
  const int bytes = static_cast<int>(pattern.size() / 8);
  cv::Mat descriptors(static_cast<int>(keypoints.size()), bytes, CV_8U, cv::Scalar(0));
  for (size_t k = 0; k < keypoints.size(); ++k) {
    const int x = static_cast<int>(std::lround(keypoints[k].pt.x));
    const int y = static_cast<int>(std::lround(keypoints[k].pt.y));
    uint8_t* out = descriptors.ptr<uint8_t>(static_cast<int>(k));
    for (size_t i = 0; i < pattern.size(); ++i) {
      const auto& p = pattern[i];
      const uint8_t a = smoothed.at<uint8_t>(y + p[1], x + p[0]);
      const uint8_t b = smoothed.at<uint8_t>(y + p[3], x + p[2]);
      if (a < b) out[i / 8] |= static_cast<uint8_t>(1u << (i % 8));
    }
  }
  return descriptors;
}

BriefExtractor::BriefExtractor(const BriefOptions& brief, const GfttOptions& gftt,
                               int max_features, double max_depth_m)
    : FeatureExtractor(max_features, max_depth_m),
      brief_(brief),
      gftt_(gftt),
      pattern_(MakeBriefPattern(brief)) {
  gftt_.Check();
}

void BriefExtractor::DetectAndDescribe(const cv::Mat& gray, std::vector<cv::KeyPoint>* keypoints,
                                       cv::Mat* descriptors) const {
  // Detect with headroom, then drop corners whose patch leaves the image.
  *keypoints = DetectGftt(gray, gftt_, 2 * max_features());
  RemoveBorderKeypoints(gray.size(), brief_.patch_size_px / 2.0f + 1.0f, keypoints);
  if (keypoints->size() > static_cast<size_t>(max_features())) keypoints->resize(max_features());
  if (keypoints->empty()) return;
  cv::Mat smoothed;
  cv::GaussianBlur(gray, smoothed, cv::Size(9, 9), brief_.smooth_sigma_px, brief_.smooth_sigma_px,
                   cv::BORDER_REFLECT_101);
  *descriptors = DescribeBrief(smoothed, *keypoints, pattern_);
}

}  // namespace duskmap
