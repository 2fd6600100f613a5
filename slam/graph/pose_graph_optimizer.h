// Optimisation of the multi-session pose graph with Ceres (spec 7): one
// problem over every link, poses on the quaternion manifold, residuals
// weighted by the square root of each link's information, optional robust loss
// on non-odometry links. The oldest (smallest id) node of each connected
// component is held fixed at its current pose, so once a loop closure links
// two sessions all of them end in the frame of the oldest one, and sessions
// not yet connected stay in their own frames.
//
// Before solving, poses can be re-initialised from the links (spec 7.3.4): a
// best-first traversal from each root expanding odometry and merged links
// before loop-closure / proximity links, pose(child) = pose(parent) * link.
//
// Afterwards the max-error check (spec 7.4, RGBD/OptimizeMaxError) runs when
// loop-closure or proximity links were added this step: if the largest
// normalised linear or angular link error exceeds max_error_ratio, the
// optimisation is rejected, the graph keeps its previous poses and the
// loop-closure / proximity links added this step are removed. When the solver
// fails, every link added this step is removed.
#pragma once

#include <vector>

#include "slam/graph/graph_errors.h"
#include "slam/graph/pose_graph.h"

namespace duskmap {

enum class RobustLoss { kNone, kHuber, kCauchy };

struct PoseGraphOptimizerOptions {
  int max_iterations = 20;             // Optimizer/Iterations
  double function_tolerance = 1e-6;    // relative cost decrease to stop (Optimizer/Epsilon, Ceres)
  RobustLoss robust_loss = RobustLoss::kNone;  // on loop-closure / proximity links (ref: none)
  double robust_loss_scale = 1.0;      // loss scale, in normalised (sigma) units
  double max_error_ratio = 3.0;        // RGBD/OptimizeMaxError; 0 disables the check
  bool initialize_from_links = true;   // re-initialise poses by traversal before solving
  int num_threads = 1;                 // Ceres threads

  void Check() const;
};

enum class OptimizationStatus {
  kOptimized,         // poses updated
  kEmptyGraph,        // nothing to do; graph unchanged
  kSolverFailed,      // Ceres failed; links added this step removed, poses unchanged
  kRejectedMaxError,  // max-error check failed; loop links added this step removed
};

const char* OptimizationStatusName(OptimizationStatus status);

struct OptimizationSummary {
  OptimizationStatus status = OptimizationStatus::kEmptyGraph;
  int num_nodes = 0;
  int num_links = 0;
  int num_components = 0;      // connected components (each with its own fixed root)
  int num_iterations = 0;
  double initial_cost = 0.0;   // Ceres cost (0.5 * sum of squared weighted residuals)
  double final_cost = 0.0;
  MaxGraphErrors max_errors;   // of the optimised poses (also when rejected)
  std::vector<LinkKey> removed_links;
  double solve_ms = 0.0;
  double total_ms = 0.0;

  bool accepted() const { return status == OptimizationStatus::kOptimized; }
};

// `links_added_this_step` lists links of `graph` added since the last
// optimisation (InputError if one is not in the graph).
OptimizationSummary OptimizePoseGraph(const PoseGraphOptimizerOptions& options,
                                      const std::vector<LinkKey>& links_added_this_step,
                                      PoseGraph* graph);

// Best-first re-initialisation of every component from its root (see above).
void InitializePosesFromLinks(PoseGraph* graph);

}  // namespace duskmap
