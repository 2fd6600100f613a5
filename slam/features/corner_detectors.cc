#include "slam/features/corner_detectors.h"

#include <algorithm>

#include <opencv2/features2d.hpp>

namespace duskmap {

std::vector<cv::KeyPoint> DetectGftt(const cv::Mat& gray, const GfttOptions& options,
                                     int max_features) {
  std::vector<cv::KeyPoint> keypoints;
  auto detector = cv::GFTTDetector::create(max_features, options.quality_level,
                                           options.min_distance_px, options.block_size,
                                           /*useHarrisDetector=*/false);
  detector->detect(gray, keypoints);
  return keypoints;
}

std::vector<cv::KeyPoint> DetectFast(const cv::Mat& gray, const FastOptions& options) {
  std::vector<cv::KeyPoint> keypoints;
  cv::FAST(gray, keypoints, options.threshold, /*nonmaxSuppression=*/true);
  return keypoints;
}

void RemoveBorderKeypoints(const cv::Size& image, float border_px,
                           std::vector<cv::KeyPoint>* keypoints) {
  const float max_x = image.width - 1 - border_px, max_y = image.height - 1 - border_px;
  keypoints->erase(std::remove_if(keypoints->begin(), keypoints->end(),
                                  [&](const cv::KeyPoint& kp) {
                                    return kp.pt.x < border_px || kp.pt.y < border_px ||
                                           kp.pt.x > max_x || kp.pt.y > max_y;
                                  }),
                   keypoints->end());
}

}  // namespace duskmap
