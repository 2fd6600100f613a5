// Measurable realism of a multi-session dataset: for SIFT and ORB (OpenCV),
// the median matching inlier ratio between frames at corresponding
// ground-truth poses across every pair of sessions.
//
// Anchors are every frame_step-th frame of the first session; in each session
// the frame nearest to an anchor (position + 0.5 m/rad x angle, within the
// gaps below) stands for it. For each pair of sessions and each anchor both
// have, descriptors are matched with Lowe's ratio test; a match is an inlier
// when the keypoint of the first frame, back-projected with its depth and
// moved by the ground-truth relative pose, reprojects within
// max_reprojection_px of its match in the second frame (matches without
// depth are left out). Ground truth instead of RANSAC makes the ratio the
// true fraction of correct matches, independent of a robust estimator.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "slam/io/dataset_reader.h"

namespace duskmap {

// The most features per frame and detector (the engine's own limit,
// FeatureOptions::max_features), and the largest reprojection threshold: a
// match beyond 100 px of ground truth is no correspondence at these sizes.
inline constexpr int kMaxRealismFeatures = 100000;
inline constexpr double kMaxRealismReprojectionPx = 100.0;

struct RealismOptions {
  int frame_step = 10;               // anchor spacing in frames of the first session
  int max_features = 1000;           // per frame and detector
  // SIFT's DoG contrast threshold: OpenCV's default 0.04; the paper's
  // experiments run SIFT at 0.02 (SIFT/ContrastThreshold, spec appendix A).
  double sift_contrast_threshold = 0.04;
  double ratio_test = 0.8;           // Lowe's nearest/second-nearest distance ratio
  double max_reprojection_px = 4.0;  // inlier threshold against ground truth
  double max_position_gap_m = 0.5;   // anchor correspondence: largest position difference
  double max_angle_gap_deg = 20.0;   // anchor correspondence: largest viewing-direction difference
  int min_correct_matches = 10;      // "SIFT finds correct matches" threshold per frame pair

  void Check() const;  // throws ConfigError naming the field and its dataset-stats flag
};

// One corresponding frame pair: an anchor seen in two sessions.
struct RealismPair {
  int session_a = 0;         // index into RealismReport::sessions, session_a < session_b
  int session_b = 0;
  int anchor = 0;            // anchor index (frame anchor * frame_step of the first session)
  int frame_a = 0;           // frame index standing for the anchor in each session
  int frame_b = 0;
  int sift_keypoints_a = 0;  // SIFT keypoints detected in each frame
  int sift_keypoints_b = 0;
  int sift_matches = 0;      // ratio-test matches whose first keypoint has depth
  int sift_correct = 0;      // of those, confirmed by ground truth
  int orb_matches = 0;
  int orb_correct = 0;
};

struct RealismReport {
  std::vector<std::string> sessions;     // names, dataset order
  std::vector<std::string> clock_times;  // "" when unknown
  int anchors = 0;
  // Symmetric matrices over sessions; the diagonal is NaN (a session against itself).
  Eigen::MatrixXd sift_inlier_ratio;     // median over corresponding frame pairs
  Eigen::MatrixXd orb_inlier_ratio;
  Eigen::MatrixXd sift_found_fraction;   // fraction of pairs with >= min_correct_matches inliers
  Eigen::MatrixXd sift_median_inliers;
  std::vector<RealismPair> pairs;        // every frame pair behind the matrices, by session pair then anchor
  double wall_s = 0.0;
};

// Throws InputError when the dataset lacks ground truth.
RealismReport ComputeRealism(const DatasetReader& dataset, const RealismOptions& options);

}  // namespace duskmap
