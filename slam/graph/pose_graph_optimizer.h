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
// The reference does so only when the optimised set of poses changed other
// than by the newest node, i.e. when a link joined two components (a session
// just got connected); otherwise it starts from the previous optimum.
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

// When the poses are re-initialised from the links before solving.
enum class PoseInitialization {
  kEveryOptimization,   // always: the result does not depend on the call history
  kWhenComponentsJoin,  // the reference's rule: only when a link added this step joins
                        // two components; otherwise start from the current poses
  kNever,               // always start from the current poses
};

// The sparse Cholesky library of Ceres' normal equations. Eigen's simplicial
// LDLT solved the six-session maps' graphs (1,000 nodes, 2,600 links, one
// iteration from a warm start) in 19 ms against CHOLMOD's 40-46 ms on the
// 2-core machine (docs/registration.md).
enum class SparseLinearAlgebra { kEigenSparse, kSuiteSparse };

struct PoseGraphOptimizerOptions {
  int max_iterations = 20;             // Optimizer/Iterations
  double function_tolerance = 1e-6;    // relative cost decrease to stop (Optimizer/Epsilon, Ceres)
  RobustLoss robust_loss = RobustLoss::kNone;  // on loop-closure / proximity links (ref: none)
  double robust_loss_scale = 1.0;      // loss scale, in normalised (sigma) units
  double max_error_ratio = 3.0;        // RGBD/OptimizeMaxError; 0 disables the check
  PoseInitialization initialization = PoseInitialization::kWhenComponentsJoin;
  SparseLinearAlgebra sparse_linear_algebra = SparseLinearAlgebra::kEigenSparse;
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
  bool reinitialized = false;  // poses re-initialised from the links before solving
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

// True when one of `added` links two nodes that no other link of `graph`
// connects, directly or through other nodes.
bool LinksJoinComponents(const PoseGraph& graph, const std::vector<LinkKey>& added);

}  // namespace duskmap
