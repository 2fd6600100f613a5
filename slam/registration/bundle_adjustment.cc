#include "slam/registration/bundle_adjustment.h"

#include <cmath>
#include <limits>
#include <memory>
#include <optional>

#include <ceres/ceres.h>
#include <ceres/rotation.h>

#include "slam/core/check.h"

namespace duskmap {
namespace {

// Pinhole projection of a camera-frame point, plus the right "virtual stereo"
// column u_r = fx * (x - b) / z + cx when kDim == 3; residual = (predicted -
// measured) / sigma.
template <int kDim, typename T>
void ProjectResidual(const PinholeCamera& camera, double baseline_m, const double* measured,
                     double sigma, const T* x, T* residuals) {
  const T inv_z = T(1.0) / x[2];
  residuals[0] = (T(camera.fx) * x[0] * inv_z + T(camera.cx) - T(measured[0])) / T(sigma);
  residuals[1] = (T(camera.fy) * x[1] * inv_z + T(camera.cy) - T(measured[1])) / T(sigma);
  if constexpr (kDim == 3) {
    residuals[2] = (T(camera.fx) * (x[0] - T(baseline_m)) * inv_z + T(camera.cx) -
                    T(measured[2])) / T(sigma);
  }
}

// Observation in the fixed map-node camera (identity pose): always stereo.
struct NodeObservationCost {
  template <typename T>
  bool operator()(const T* point, T* residuals) const {
    ProjectResidual<3>(camera, baseline_m, measured, sigma, point, residuals);
    return true;
  }
  PinholeCamera camera;
  double baseline_m;
  double measured[3];
  double sigma;
};

// Observation in the query camera; q = query_from_node rotation (x, y, z, w),
// t = its translation.
template <int kDim>
struct QueryObservationCost {
  template <typename T>
  bool operator()(const T* q, const T* t, const T* point, T* residuals) const {
    const T wxyz[4] = {q[3], q[0], q[1], q[2]};
    T x[3];
    ceres::QuaternionRotatePoint(wxyz, point, x);
    for (int i = 0; i < 3; ++i) x[i] += t[i];
    ProjectResidual<kDim>(camera, baseline_m, measured, sigma, x, residuals);
    return true;
  }
  PinholeCamera camera;
  double baseline_m;
  double measured[3];
  double sigma;
};

struct BaState {
  Eigen::Quaterniond rotation;
  Eigen::Vector3d translation;
  std::vector<Eigen::Vector3d> points;
};

struct ObservationBlocks {
  ceres::ResidualBlockId node;
  ceres::ResidualBlockId query;
};

// Adds the residuals of the active correspondences to `problem`.
std::vector<ObservationBlocks> BuildProblem(const LocalBundleAdjustmentOptions& options,
                                            const std::vector<BundleAdjustmentCorrespondence>& c,
                                            const std::vector<int>& active,
                                            const PinholeCamera& node_camera,
                                            const PinholeCamera& query_camera, BaState* state,
                                            ceres::Problem* problem) {
  std::vector<ObservationBlocks> blocks;
  const double b = options.stereo_baseline_m;
  const double sigma = options.pixel_sigma_px;
  problem->AddParameterBlock(state->rotation.coeffs().data(), 4,
                             new ceres::EigenQuaternionManifold);
  problem->AddParameterBlock(state->translation.data(), 3);
  for (int k : active) {
    const BundleAdjustmentCorrespondence& obs = c[k];
    double* point = state->points[k].data();
    const double node_depth = obs.point_in_node.z();
    auto* node_cost = new ceres::AutoDiffCostFunction<NodeObservationCost, 3, 3>(
        new NodeObservationCost{node_camera, b,
                                {obs.pixel_in_node.x(), obs.pixel_in_node.y(),
                                 obs.pixel_in_node.x() - node_camera.fx * b / node_depth},
                                sigma});
    ObservationBlocks ids;
    ids.node = problem->AddResidualBlock(
        node_cost, new ceres::HuberLoss(options.huber_delta_px), point);
    ceres::CostFunction* query_cost = nullptr;
    const double query_depth = obs.point_in_query.z();
    if (obs.point_in_query.allFinite() && query_depth > 0.0) {
      query_cost = new ceres::AutoDiffCostFunction<QueryObservationCost<3>, 3, 4, 3, 3>(
          new QueryObservationCost<3>{query_camera, b,
                                      {obs.pixel_in_query.x(), obs.pixel_in_query.y(),
                                       obs.pixel_in_query.x() - query_camera.fx * b / query_depth},
                                      sigma});
    } else {
      query_cost = new ceres::AutoDiffCostFunction<QueryObservationCost<2>, 2, 4, 3, 3>(
          new QueryObservationCost<2>{query_camera, b,
                                      {obs.pixel_in_query.x(), obs.pixel_in_query.y(), 0.0},
                                      sigma});
    }
    ids.query = problem->AddResidualBlock(query_cost, new ceres::HuberLoss(options.huber_delta_px),
                                          state->rotation.coeffs().data(),
                                          state->translation.data(), point);
    blocks.push_back(ids);
  }
  return blocks;
}

// Squared normalised (unrobustified) error of one residual block.
double SquaredError(const ceres::Problem& problem, ceres::ResidualBlockId id) {
  double residuals[3] = {0.0, 0.0, 0.0};
  double cost = 0.0;
  if (!problem.EvaluateResidualBlockAssumingParametersUnchanged(id, false, &cost, residuals,
                                                                nullptr)) {
    return std::numeric_limits<double>::infinity();
  }
  const int size = problem.GetCostFunctionForResidualBlock(id)->num_residuals();
  double sum = 0.0;
  for (int i = 0; i < size; ++i) sum += residuals[i] * residuals[i];
  return std::isfinite(sum) ? sum : std::numeric_limits<double>::infinity();
}

// Runs `iterations` of LM on the active set, then returns the correspondences
// whose two observations are both within outlier_chi2; nullopt when the
// solver fails.
std::optional<std::vector<int>> SolveAndSelect(const LocalBundleAdjustmentOptions& options,
                                const std::vector<BundleAdjustmentCorrespondence>& c,
                                const std::vector<int>& active, const PinholeCamera& node_camera,
                                const PinholeCamera& query_camera, int iterations,
                                BaState* state, BundleAdjustmentResult* result) {
  ceres::Problem problem;
  const std::vector<ObservationBlocks> blocks =
      BuildProblem(options, c, active, node_camera, query_camera, state, &problem);
  ceres::Solver::Options solver;
  solver.linear_solver_type = ceres::DENSE_SCHUR;
  // Points are eliminated first; giving the ordering skips Ceres's search for
  // an independent set.
  auto ordering = std::make_shared<ceres::ParameterBlockOrdering>();
  for (int k : active) ordering->AddElementToGroup(state->points[k].data(), 0);
  ordering->AddElementToGroup(state->rotation.coeffs().data(), 1);
  ordering->AddElementToGroup(state->translation.data(), 1);
  solver.linear_solver_ordering = ordering;
  solver.max_num_iterations = iterations;
  solver.num_threads = 1;
  solver.logging_type = ceres::SILENT;
  solver.minimizer_progress_to_stdout = false;
  ceres::Solver::Summary summary;
  ceres::Solve(solver, &problem, &summary);
  if (result->num_iterations == 0) result->initial_cost = summary.initial_cost;
  result->final_cost = summary.final_cost;
  result->num_iterations += static_cast<int>(summary.iterations.size());
  if (!summary.IsSolutionUsable()) return std::nullopt;
  std::vector<int> kept;
  for (size_t i = 0; i < active.size(); ++i) {
    if (SquaredError(problem, blocks[i].node) <= options.outlier_chi2 &&
        SquaredError(problem, blocks[i].query) <= options.outlier_chi2) {
      kept.push_back(active[i]);
    }
  }
  return kept;
}

}  // namespace

void LocalBundleAdjustmentOptions::Check() const {
  SLAM_THROW_IF_NOT(ConfigError, pixel_sigma_px > 0.0)
      << "LocalBundleAdjustmentOptions.pixel_sigma_px: must be > 0, got " << pixel_sigma_px;
  SLAM_THROW_IF_NOT(ConfigError, huber_delta_px > 0.0)
      << "LocalBundleAdjustmentOptions.huber_delta_px: must be > 0, got " << huber_delta_px;
  SLAM_THROW_IF_NOT(ConfigError, outlier_chi2 > 0.0)
      << "LocalBundleAdjustmentOptions.outlier_chi2: must be > 0, got " << outlier_chi2;
  SLAM_THROW_IF_NOT(ConfigError, stereo_baseline_m > 0.0)
      << "LocalBundleAdjustmentOptions.stereo_baseline_m: must be > 0, got "
      << stereo_baseline_m;
  SLAM_THROW_IF_NOT(ConfigError, first_iterations >= 1)
      << "LocalBundleAdjustmentOptions.first_iterations: must be >= 1, got "
      << first_iterations;
  SLAM_THROW_IF_NOT(ConfigError, iterations >= 1)
      << "LocalBundleAdjustmentOptions.iterations: must be >= 1, got " << iterations;
}

BundleAdjustmentResult RefineTwoViewBundleAdjustment(
    const LocalBundleAdjustmentOptions& options,
    const std::vector<BundleAdjustmentCorrespondence>& correspondences,
    const PinholeCamera& node_camera, const PinholeCamera& query_camera,
    const Rigid3d& query_from_node_guess) {
  options.Check();
  SLAM_CHECK(node_camera.IsValid() && query_camera.IsValid());
  SLAM_CHECK(query_from_node_guess.IsFinite());
  BundleAdjustmentResult result;
  BaState state{query_from_node_guess.rotation, query_from_node_guess.translation, {}};
  std::vector<int> active;
  for (size_t k = 0; k < correspondences.size(); ++k) {
    const BundleAdjustmentCorrespondence& c = correspondences[k];
    SLAM_CHECK(c.point_in_node.allFinite() && c.pixel_in_node.allFinite() &&
               c.pixel_in_query.allFinite());
    state.points.push_back(c.point_in_node);
    if (c.point_in_node.z() > 0.0) active.push_back(static_cast<int>(k));
  }
  if (active.empty()) return result;
  std::optional<std::vector<int>> kept =
      SolveAndSelect(options, correspondences, active, node_camera, query_camera,
                     options.first_iterations, &state, &result);
  if (!kept) return result;
  if (!kept->empty()) {
    kept = SolveAndSelect(options, correspondences, *kept, node_camera, query_camera,
                          options.iterations, &state, &result);
    if (!kept) return result;
  }
  const Rigid3d refined(state.rotation, state.translation);
  if (!refined.IsFinite()) return result;
  result.success = true;
  result.query_from_node = refined;
  result.inliers = std::move(*kept);
  return result;
}

}  // namespace duskmap
