// Square patches of a gray image around keypoints, at each keypoint's scale
// and orientation: the input of a patch descriptor network (the `patch`
// contract of the onnx types, onnx_patch_extractor.h) and of its training
// data (slam/training/), which must sample exactly the same way.
//
// A patch of patch_size_px x patch_size_px pixels covers a square of side
// support_per_size x KeyPoint::size image pixels centred on KeyPoint::pt,
// turned by KeyPoint::angle (OpenCV's convention, degrees) so that a
// keypoint's orientation is the patch's +x axis. It is sampled bilinearly
// from the level of a Gaussian pyramid (cv::pyrDown) at which one patch
// pixel spans one to two level pixels, so that large keypoints are not
// aliased; outside the image the border is replicated.
#pragma once

#include <vector>

#include <opencv2/core.hpp>

namespace duskmap {

struct PatchSamplerOptions {
  int patch_size_px = 32;
  // The patch's side in image pixels per pixel of KeyPoint::size (OpenCV's
  // SIFT describes 6 sizes: 4 bins of 3 sigma, size = 2 sigma).
  double support_per_size = 6.0;
  bool oriented = true;  // false: angle ignored (upright patches)
  void Check() const;    // throws ConfigError "<field>: problem"
};

class PatchSampler {
 public:
  // `gray`: 8-bit single-channel, non-empty. Builds the pyramid once.
  PatchSampler(const cv::Mat& gray, const PatchSamplerOptions& options);

  // One CV_8U row of patch_size_px^2 values (row-major patch) per keypoint,
  // in the keypoints' order; an empty 0 x patch_size_px^2 matrix for none.
  cv::Mat Sample(const std::vector<cv::KeyPoint>& keypoints) const;

  const PatchSamplerOptions& options() const { return options_; }

 private:
  PatchSamplerOptions options_;
  std::vector<cv::Mat> pyramid_;  // level 0 = the image
};

}  // namespace duskmap
