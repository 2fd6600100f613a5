// Detector/descriptor quality between two images related by a known
// homography (target ~ H * reference), as in the Oxford/HPatches protocols:
// repeatability (SuperPoint's symmetric definition), matching score, mean
// matching accuracy (D2-Net) and homography-estimation correctness
// (SuperPoint's mean corner error).
#pragma once

#include <array>
#include <vector>

#include <opencv2/core.hpp>

#include "slam/features/frame_features.h"

namespace duskmap {

struct HomographyMetricsOptions {
  double repeatability_px = 3.0;         // keypoint distance counted as repeated, pixels
  double correct_match_px = 3.0;         // reprojection error of a correct match, pixels
  std::array<double, 3> mma_px = {1.0, 3.0, 5.0};  // MMA thresholds, pixels
  double ransac_px = 3.0;                // RANSAC inlier threshold of findHomography, pixels
  double corner_error_px = 3.0;          // homography counted correct below this, pixels
  void Check() const;
};

struct PairMetrics {
  int reference_keypoints = 0;
  int target_keypoints = 0;
  int matches = 0;          // mutual nearest neighbours
  int correct_matches = 0;  // with error < correct_match_px
  double repeatability = 0.0;
  double matching_score = 0.0;  // correct matches / min(visible keypoints of each image)
  std::array<double, 3> mma = {0.0, 0.0, 0.0};
  bool homography_estimated = false;
  double corner_error_px = 0.0;  // mean corner distance; only when estimated
  bool homography_correct = false;
};

// Maps a point through a 3x3 CV_64F homography.
cv::Point2d ApplyHomography(const cv::Matx33d& h, const cv::Point2d& p);

// Mutual nearest neighbours by L2 (float) or Hamming (binary) distance;
// queryIdx indexes `a`, trainIdx `b`.
std::vector<cv::DMatch> MutualNearestMatches(const FrameFeatures& a, const FrameFeatures& b);

// Symmetric repeatability: the fraction of keypoints, over both images, whose
// projection into the other image lies within tolerance_px of one of its
// keypoints; only keypoints projecting inside the other image count.
double Repeatability(const std::vector<cv::KeyPoint>& reference, const cv::Size& reference_size,
                     const std::vector<cv::KeyPoint>& target, const cv::Size& target_size,
                     const cv::Matx33d& target_from_reference, double tolerance_px);

PairMetrics EvaluatePair(const FrameFeatures& reference, const cv::Size& reference_size,
                         const FrameFeatures& target, const cv::Size& target_size,
                         const cv::Matx33d& target_from_reference,
                         const HomographyMetricsOptions& options);

}  // namespace duskmap
