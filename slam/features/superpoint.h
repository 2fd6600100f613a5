// SuperPoint (DeTone, Malisiewicz, Rabinovich, CVPRW 2018) run through
// OpenCV's DNN module from an ONNX file. The network takes a 1x1xHxW gray
// image in [0, 1] (H, W multiples of 8; the input is padded) and returns the
// 65-channel detector logits ("semi", 1x65xH/8xW/8) and the 256-channel
// descriptor map (1x256xH/8xW/8). Decoding follows the reference
// (spec §1.2): channel softmax, drop the dustbin, depth-to-space to full
// resolution, max-pool NMS of radius nms_radius_px with two suppression
// passes, score > threshold, border removal; descriptors are bilinearly
// sampled from the coarse map and L2-normalised.
#pragma once

#include <memory>
#include <mutex>

#include <opencv2/dnn.hpp>

#include "slam/features/feature_extractor.h"

namespace duskmap {

// Full-resolution heat map (CV_32F, rows = 8 * semi rows) from the logits.
cv::Mat DecodeSuperPointHeatmap(const cv::Mat& semi);
// Max-pool non-maximum suppression of `scores` (two suppression passes).
cv::Mat SuperPointNms(const cv::Mat& scores, int radius_px);
// Bilinear samples of the (1x256xHcxWc) descriptor map at keypoints given
// in full-resolution pixels, L2-normalised; one CV_32F row each.
cv::Mat SampleSuperPointDescriptors(const cv::Mat& desc, const std::vector<cv::KeyPoint>& keypoints);

class SuperPointExtractor : public FeatureExtractor {
 public:
  // Loads options.model_path; throws InputError when it is missing or is
  // not a SuperPoint-shaped network.
  SuperPointExtractor(const SuperPointOptions& options, int max_features, double max_depth_m = 0.0);
  std::string name() const override { return "superpoint"; }
  DescriptorKind kind() const override { return DescriptorKind::kFloat; }

 protected:
  void DetectAndDescribe(const cv::Mat& gray, std::vector<cv::KeyPoint>* keypoints,
                         cv::Mat* descriptors) const override;

 private:
  // Runs the network; returns semi and desc blobs.
  void Forward(const cv::Mat& input, cv::Mat* semi, cv::Mat* desc) const;

  SuperPointOptions options_;
  mutable cv::dnn::Net net_;  // forward() is non-const in OpenCV
  mutable std::mutex mutex_;
};

}  // namespace duskmap
