// Absolute pose from 3D-2D correspondences: a P3P/AP3P minimal solver inside
// the generic seeded RANSAC loop (ransac.h), refitted on its inliers with
// Levenberg-Marquardt on the reprojection error.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "slam/core/camera.h"
#include "slam/core/rigid3.h"

namespace duskmap {

enum class PnpMinimalSolver {
  kP3P,   // Gao et al. 2003 (cv::solveP3P, SOLVEPNP_P3P)
  kAP3P,  // Ke & Roumeliotis 2017 (cv::solveP3P, SOLVEPNP_AP3P)
};

struct PnpRansacOptions {
  // Inlier threshold on the reprojection error, px. The reference compares
  // its unsquared error with Vis/PnPReprojError^2 = 4 px (spec 6.3).
  double max_reprojection_error_px = 4.0;
  double confidence = 0.99;  // adaptive-trial confidence (reference 0.99)
  int max_trials = 300;      // reference Vis/Iterations
  int refine_rounds = 2;     // LM refit on inliers, then re-select, this many times
  PnpMinimalSolver solver = PnpMinimalSolver::kAP3P;
  uint64_t random_seed = 0;  // RANSAC sampling seed

  void Check() const;
};

struct PnpResult {
  bool success = false;         // at least 4 inliers and a finite pose
  Rigid3d camera_from_points;   // maps the 3D points' frame into the camera frame
  std::vector<int> inliers;     // indices into the correspondences
  int num_trials = 0;
};

// points[i] (any frame P, metres) is observed at pixels[i] by `camera`.
// Returns camera_from_P. Non-finite inputs must be filtered by the caller
// (SLAM_CHECK). Fewer than 4 correspondences give success = false.
PnpResult EstimatePnpRansac(const PnpRansacOptions& options,
                            const std::vector<Eigen::Vector3d>& points,
                            const std::vector<Eigen::Vector2d>& pixels,
                            const PinholeCamera& camera);

// Reprojection error in px of one point under camera_from_points; +inf when
// the point is not in front of the camera.
double ReprojectionErrorPx(const PinholeCamera& camera, const Rigid3d& camera_from_points,
                           const Eigen::Vector3d& point, const Eigen::Vector2d& pixel);

}  // namespace duskmap
