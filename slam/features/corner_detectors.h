// Corner detectors used under the binary descriptors, with the reference's
// settings (spec §1.2): GFTT (min-eigenvalue, strongest first) and FAST.
#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "slam/features/feature_options.h"

namespace duskmap {

// At most max_features GFTT corners, strongest first; KeyPoint.size is the
// block size, response the corner quality.
std::vector<cv::KeyPoint> DetectGftt(const cv::Mat& gray, const GfttOptions& options,
                                     int max_features);

// FAST-9 corners with non-maximum suppression (no cap; callers limit).
std::vector<cv::KeyPoint> DetectFast(const cv::Mat& gray, const FastOptions& options);

// Removes keypoints closer than border_px to the image border.
void RemoveBorderKeypoints(const cv::Size& image, float border_px,
                           std::vector<cv::KeyPoint>* keypoints);

}  // namespace duskmap
