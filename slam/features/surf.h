// Own SURF (Bay, Ess, Tuytelaars, Van Gool, "Speeded-Up Robust Features",
// CVIU 2008), as OpenCV's SURF computes it (the reference's runs; details in
// docs/features.md): Fast-Hessian detection with box filters on an integral image,
// orientation from Haar responses in a sliding 60-degree window, and the
// 64-D (or extended 128-D) descriptor of Haar sums over 4x4 subregions.
// KeyPoint.size is the box-filter side in pixels (scale s = 1.2 * size / 9),
// KeyPoint.response the Hessian determinant, KeyPoint.angle in degrees.
#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "slam/features/feature_extractor.h"
#include "slam/features/feature_registry.h"
#include "slam/features/integral_image.h"

namespace duskmap {

// Side in pixels of the box filter of `layer` (0 to octave_layers + 1) in
// `octave`: 9, 15, 21, 27 in octave 0, each octave doubling the previous
// one's (18, 30, 42, 54; 36, ...), as OpenCV's SURF builds its scale space
// (Bay et al.'s paper steps octave o by 6 * 2^o from 15 instead: 15, 27, 39,
// 51). Octave o is sampled every 2^o pixels.
int SurfFilterSide(int octave, int layer);

// Fast-Hessian keypoints, the `max_features` strongest, with orientation
// (angle 0 when options.upright).
std::vector<cv::KeyPoint> DetectSurfKeypoints(const IntegralImage& integral,
                                              const SurfOptions& options, int max_features);

// One CV_32F row (64 or 128 values, unit L2 norm, or all zero on a flat
// patch) per keypoint of the 8-bit grey image, oriented by KeyPoint.angle
// (axis-aligned when `upright`).
cv::Mat DescribeSurf(const cv::Mat& gray, const std::vector<cv::KeyPoint>& keypoints,
                     bool extended, bool upright);

class SurfExtractor : public FeatureExtractor {
 public:
  SurfExtractor(const SurfOptions& options, int max_features, double max_depth_m = 0.0);
  std::string name() const override { 
    return FeatureTypeName(FeatureTypeId::kSurf) + (options_.upright ? "-upright" : "");
  }
  DescriptorKind kind() const override { return DescriptorKind::kFloat; }

 protected:
  void DetectAndDescribe(const cv::Mat& gray, std::vector<cv::KeyPoint>* keypoints,
                         cv::Mat* descriptors) const override;

 private:
  SurfOptions options_;
};

}  // namespace duskmap
