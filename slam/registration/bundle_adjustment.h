// Two-view local bundle adjustment of a registration (spec 6.5, reference
// OptimizerG2O::optimizeBA): the map node's camera is fixed at the origin,
// the query camera pose and the inlier 3D points are optimised.
// Observations: in the map node, "stereo" (u, v, u - fx * b / depth) with a
// virtual baseline b so that the measured depth constrains the point; in the
// query, stereo when the query has depth there, else mono (u, v). Residuals in
// px / pixel_sigma_px under a Huber loss. After `first_iterations`, and again
// after `iterations`, observations whose squared normalised error exceeds
// outlier_chi2 are marked outliers and their correspondences dropped.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "slam/core/camera.h"
#include "slam/core/rigid3.h"

namespace duskmap {

struct LocalBundleAdjustmentOptions {
  bool enabled = true;              // reference Vis/BundleAdjustment = 1
  double pixel_sigma_px = 1.0;      // observation std dev (g2o/PixelVariance = 1), px
  double huber_delta_px = 8.0;      // Huber threshold on the normalised residual norm
  double outlier_chi2 = 8.0;        // squared normalised error above which an observation is an outlier
  double stereo_baseline_m = 0.075; // virtual stereo baseline for depth observations (g2o/Baseline), m
  int first_iterations = 5;         // LM iterations before the first outlier marking
  int iterations = 20;              // LM iterations after it (Optimizer/Iterations)

  void Check() const;
};

struct BundleAdjustmentCorrespondence {
  Eigen::Vector3d point_in_node;   // finite, from the map node's depth, metres
  Eigen::Vector2d pixel_in_node;   // map node keypoint, px
  Eigen::Vector2d pixel_in_query;  // query keypoint, px
  Eigen::Vector3d point_in_query;  // query 3D point, metres; NaN when the query has no depth
};

struct BundleAdjustmentResult {
  bool success = false;        // the solver ran and returned a finite pose
  Rigid3d query_from_node;     // refined query camera pose
  std::vector<int> inliers;    // indices of the correspondences kept
  int num_iterations = 0;      // LM iterations run in total
  double initial_cost = 0.0;   // Ceres cost (0.5 * sum of robustified squared residuals)
  double final_cost = 0.0;
};

BundleAdjustmentResult RefineTwoViewBundleAdjustment(
    const LocalBundleAdjustmentOptions& options,
    const std::vector<BundleAdjustmentCorrespondence>& correspondences,
    const PinholeCamera& node_camera, const PinholeCamera& query_camera,
    const Rigid3d& query_from_node_guess);

}  // namespace duskmap
