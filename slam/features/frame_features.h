// The features of one frame: keypoints (strongest first), their descriptors
// and, where registered depth exists, their 3D points in the camera frame.
// This is the contract between feature extraction and every consumer
// (vocabulary, registration, map store).
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

namespace duskmap {

enum class DescriptorKind {
  kFloat,   // CV_32F rows, compared with L2 distance
  kBinary,  // CV_8U rows, compared with Hamming distance
};

struct FrameFeatures {
  std::vector<cv::KeyPoint> keypoints;  // sorted by response, strongest first
  cv::Mat descriptors;                  // one row per keypoint (CV_32F or CV_8U)
  DescriptorKind kind = DescriptorKind::kFloat;
  // One per keypoint, in the camera frame, metres; NaN where depth is missing.
  std::vector<Eigen::Vector3f> points_in_camera;

  size_t size() const { return keypoints.size(); }
  bool empty() const { return keypoints.empty(); }
  // Bytes one descriptor occupies as stored.
  size_t DescriptorBytes() const {
    return descriptors.empty() ? 0 : descriptors.cols * descriptors.elemSize();
  }
  bool HasPoint(size_t i) const { return points_in_camera[i].allFinite(); }
};

}  // namespace duskmap
