// Own SURF (Bay, Ess, Tuytelaars, Van Gool, "Speeded-Up Robust Features",
// CVIU 2008): Fast-Hessian detection with box filters on an integral image,
// orientation from Haar responses in a sliding 60-degree window, and the
// 64-D (or extended 128-D) descriptor of Haar sums over 4x4 subregions.
// KeyPoint.size is the box-filter side in pixels (scale s = 1.2 * size / 9),
// KeyPoint.response the Hessian determinant, KeyPoint.angle in degrees.
#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "slam/features/feature_extractor.h"
#include "slam/features/integral_image.h"

namespace duskmap {

// Fast-Hessian keypoints, the `max_features` strongest, with orientation
// (angle 0 when options.upright).
std::vector<cv::KeyPoint> DetectSurfKeypoints(const IntegralImage& integral,
                                              const SurfOptions& options, int max_features);

// One CV_32F row (64 or 128 values, unit L2 norm, or all zero on a flat
// patch) per keypoint, oriented by KeyPoint.angle.
cv::Mat DescribeSurf(const IntegralImage& integral, const std::vector<cv::KeyPoint>& keypoints,
                     bool extended);

class SurfExtractor : public FeatureExtractor {
 public:
  SurfExtractor(const SurfOptions& options, int max_features, double max_depth_m = 0.0);
  std::string name() const override { return options_.upright ? "surf-upright" : "surf"; }
  DescriptorKind kind() const override { return DescriptorKind::kFloat; }

 protected:
  void DetectAndDescribe(const cv::Mat& gray, std::vector<cv::KeyPoint>* keypoints,
                         cv::Mat* descriptors) const override;

 private:
  SurfOptions options_;
};

}  // namespace duskmap
