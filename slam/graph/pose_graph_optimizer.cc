#include "slam/graph/pose_graph_optimizer.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <queue>
#include <unordered_map>

#include <ceres/ceres.h>

#include "slam/core/check.h"
#include "slam/core/timer.h"
#include "slam/graph/pose_graph_error_term.h"

namespace duskmap {
namespace {

bool IsLoopLink(LinkType type) {
  return type == LinkType::kLoopClosure || type == LinkType::kProximity;
}

int TraversalRank(LinkType type) {
  switch (type) {
    case LinkType::kOdometry: return 0;
    case LinkType::kMerged:
    case LinkType::kPrior: return 1;
    case LinkType::kLoopClosure:
    case LinkType::kProximity: return 2;
  }
  return 3;
}

// Ceres parameter storage for every node of the graph.
struct PoseParameters {
  std::unordered_map<NodeId, size_t> index;
  std::vector<Eigen::Vector3d> translations;
  std::vector<Eigen::Quaterniond> rotations;

  explicit PoseParameters(const PoseGraph& graph) {
    index.reserve(graph.num_nodes());
    for (const auto& [id, node] : graph.nodes()) {
      index[id] = translations.size();
      translations.push_back(node.world_from_node.translation);
      rotations.push_back(node.world_from_node.rotation);
    }
  }
  double* p(NodeId id) { return translations[index.at(id)].data(); }
  double* q(NodeId id) { return rotations[index.at(id)].coeffs().data(); }
  bool AllFinite() const {
    for (size_t i = 0; i < translations.size(); ++i) {
      if (!translations[i].allFinite() || !rotations[i].coeffs().allFinite()) return false;
    }
    return true;
  }
};

ceres::LossFunction* MakeLoss(const PoseGraphOptimizerOptions& options, LinkType type) {
  if (!IsLoopLink(type)) return nullptr;
  switch (options.robust_loss) {
    case RobustLoss::kNone: return nullptr;
    case RobustLoss::kHuber: return new ceres::HuberLoss(options.robust_loss_scale);
    case RobustLoss::kCauchy: return new ceres::CauchyLoss(options.robust_loss_scale);
  }
  return nullptr;
}

void BuildProblem(const PoseGraphOptimizerOptions& options, const PoseGraph& graph,
                  PoseParameters* params, ceres::Problem* problem) {
  if (graph.links().empty()) return;
  ceres::Manifold* quaternion_manifold = new ceres::EigenQuaternionManifold;  // owned by problem
  for (const auto& [key, link] : graph.links()) {
    // information = L L^T, so sqrt_information = L^T gives r^T information r.
    const Eigen::Matrix<double, 6, 6> sqrt_information =
        link.information.llt().matrixL().transpose();
    problem->AddResidualBlock(RelativePoseError::Create(link.from_from_to, sqrt_information),
                              MakeLoss(options, link.type), params->p(link.from),
                              params->q(link.from), params->p(link.to), params->q(link.to));
  }
  for (const auto& [id, node] : graph.nodes()) {
    if (problem->HasParameterBlock(params->q(id))) {
      problem->SetManifold(params->q(id), quaternion_manifold);
    }
  }
  // Gauge: the oldest node of each component keeps its pose.
  for (const std::vector<NodeId>& component : graph.ConnectedComponents()) {
    if (component.size() < 2) continue;
    problem->SetParameterBlockConstant(params->p(component.front()));
    problem->SetParameterBlockConstant(params->q(component.front()));
  }
}

ceres::Solver::Options SolverOptions(const PoseGraphOptimizerOptions& options) {
  ceres::Solver::Options solver;
  solver.max_num_iterations = options.max_iterations;
  solver.function_tolerance = options.function_tolerance;
  solver.num_threads = options.num_threads;
  solver.logging_type = ceres::SILENT;
  solver.minimizer_progress_to_stdout = false;
  solver.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  solver.sparse_linear_algebra_library_type =
      options.sparse_linear_algebra == SparseLinearAlgebra::kSuiteSparse ? ceres::SUITE_SPARSE
                                                                         : ceres::EIGEN_SPARSE;
  return solver;
}

void RemoveLinks(const std::vector<LinkKey>& keys, bool loop_links_only, PoseGraph* graph,
                 OptimizationSummary* summary) {
  for (const LinkKey& key : keys) {
    if (loop_links_only && !IsLoopLink(key.type)) continue;
    if (graph->RemoveLink(key)) summary->removed_links.push_back(key);
  }
}

}  // namespace

void PoseGraphOptimizerOptions::Check() const {
  SLAM_THROW_IF_NOT(ConfigError, max_iterations >= 1)
      << "PoseGraphOptimizerOptions.max_iterations: must be >= 1, got " << max_iterations;
  SLAM_THROW_IF_NOT(ConfigError, function_tolerance >= 0.0)
      << "PoseGraphOptimizerOptions.function_tolerance: must be >= 0, got "
      << function_tolerance;
  SLAM_THROW_IF_NOT(ConfigError, robust_loss_scale > 0.0)
      << "PoseGraphOptimizerOptions.robust_loss_scale: must be > 0, got " << robust_loss_scale;
  SLAM_THROW_IF_NOT(ConfigError, max_error_ratio >= 0.0)
      << "PoseGraphOptimizerOptions.max_error_ratio: must be >= 0, got " << max_error_ratio;
  SLAM_THROW_IF_NOT(ConfigError,
                    sparse_linear_algebra != SparseLinearAlgebra::kSuiteSparse ||
                        ceres::IsSparseLinearAlgebraLibraryTypeAvailable(ceres::SUITE_SPARSE))
      << "PoseGraphOptimizerOptions.sparse_linear_algebra: this Ceres has no SuiteSparse";
  SLAM_THROW_IF_NOT(ConfigError, num_threads >= 1)
      << "PoseGraphOptimizerOptions.num_threads: must be >= 1, got " << num_threads;
}

const char* OptimizationStatusName(OptimizationStatus status) {
  switch (status) {
    case OptimizationStatus::kOptimized: return "optimized";
    case OptimizationStatus::kEmptyGraph: return "empty_graph";
    case OptimizationStatus::kSolverFailed: return "solver_failed";
    case OptimizationStatus::kRejectedMaxError: return "rejected_max_error";
  }
  return "unknown";
}

void InitializePosesFromLinks(PoseGraph* graph) {
  SLAM_CHECK(graph != nullptr);
  struct Entry {
    int rank;
    size_t order;
    NodeId id;
    Rigid3d world_from_node;
    bool operator>(const Entry& o) const {
      return rank != o.rank ? rank > o.rank : order > o.order;
    }
  };
  for (const std::vector<NodeId>& component : graph->ConnectedComponents()) {
    std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> frontier;
    std::unordered_map<NodeId, bool> done;
    size_t order = 0;
    frontier.push({0, order++, component.front(), graph->node(component.front()).world_from_node});
    while (!frontier.empty()) {
      const Entry entry = frontier.top();
      frontier.pop();
      if (done[entry.id]) continue;
      done[entry.id] = true;
      graph->SetPose(entry.id, entry.world_from_node);
      for (const LinkKey& key : graph->LinksOf(entry.id)) {
        const Link& link = graph->links().at(key);
        const bool forward = link.from == entry.id;
        const NodeId other = forward ? link.to : link.from;
        if (done[other]) continue;
        const Rigid3d world_from_other =
            entry.world_from_node *
            (forward ? link.from_from_to : link.from_from_to.Inverse());
        frontier.push({TraversalRank(link.type), order++, other, world_from_other});
      }
    }
  }
}

bool LinksJoinComponents(const PoseGraph& graph, const std::vector<LinkKey>& added) {
  if (added.empty()) return false;
  std::unordered_map<NodeId, NodeId> parent;
  parent.reserve(graph.num_nodes());
  for (const auto& [id, node] : graph.nodes()) parent[id] = id;
  const auto find = [&parent](NodeId id) {
    while (parent[id] != id) id = parent[id] = parent[parent[id]];
    return id;
  };
  std::vector<LinkKey> sorted_added = added;
  std::sort(sorted_added.begin(), sorted_added.end());
  for (const auto& [key, link] : graph.links()) {
    if (std::binary_search(sorted_added.begin(), sorted_added.end(), key)) continue;
    const NodeId a = find(link.from), b = find(link.to);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
  for (const LinkKey& key : added) {
    if (graph.HasLink(key) && find(key.from) != find(key.to)) return true;
  }
  return false;
}

namespace {

bool ShouldInitialize(const PoseGraphOptimizerOptions& options, const PoseGraph& graph,
                      const std::vector<LinkKey>& added) {
  switch (options.initialization) {
    case PoseInitialization::kEveryOptimization: return true;
    case PoseInitialization::kWhenComponentsJoin: return LinksJoinComponents(graph, added);
    case PoseInitialization::kNever: return false;
  }
  return true;
}

}  // namespace

OptimizationSummary OptimizePoseGraph(const PoseGraphOptimizerOptions& options,
                                      const std::vector<LinkKey>& links_added_this_step,
                                      PoseGraph* graph) {
  options.Check();
  SLAM_CHECK(graph != nullptr);
  const Stopwatch total;
  OptimizationSummary summary;
  for (const LinkKey& key : links_added_this_step) {
    SLAM_THROW_IF_NOT(InputError, graph->HasLink(key))
        << "pose graph optimisation: added link " << key.from << "->" << key.to << " ("
        << LinkTypeName(key.type) << ") is not in the graph";
  }
  summary.num_nodes = static_cast<int>(graph->num_nodes());
  summary.num_links = static_cast<int>(graph->num_links());
  if (graph->empty()) {
    summary.status = OptimizationStatus::kEmptyGraph;
    summary.total_ms = total.ElapsedMs();
    return summary;
  }
  summary.num_components = static_cast<int>(graph->ConnectedComponents().size());

  PoseGraph candidate = *graph;
  summary.reinitialized = ShouldInitialize(options, candidate, links_added_this_step);
  if (summary.reinitialized) InitializePosesFromLinks(&candidate);
  PoseParameters params(candidate);
  ceres::Problem problem;
  BuildProblem(options, candidate, &params, &problem);
  bool solved = true;
  if (problem.NumResidualBlocks() > 0) {
    const Stopwatch solve;
    ceres::Solver::Summary ceres_summary;
    ceres::Solve(SolverOptions(options), &problem, &ceres_summary);
    summary.solve_ms = solve.ElapsedMs();
    summary.num_iterations = static_cast<int>(ceres_summary.iterations.size());
    summary.initial_cost = ceres_summary.initial_cost;
    summary.final_cost = ceres_summary.final_cost;
    solved = ceres_summary.IsSolutionUsable() && params.AllFinite();
  }
  if (!solved) {
    RemoveLinks(links_added_this_step, /*loop_links_only=*/false, graph, &summary);
    summary.status = OptimizationStatus::kSolverFailed;
    summary.total_ms = total.ElapsedMs();
    return summary;
  }
  for (const auto& [id, index] : params.index) {
    candidate.SetPose(id, Rigid3d(params.rotations[index], params.translations[index]));
  }
  summary.max_errors = ComputeMaxGraphErrors(candidate);

  bool loop_added = false;
  for (const LinkKey& key : links_added_this_step) loop_added |= IsLoopLink(key.type);
  const bool too_large = summary.max_errors.linear.ratio > options.max_error_ratio ||
                         summary.max_errors.angular.ratio > options.max_error_ratio;
  if (options.max_error_ratio > 0.0 && loop_added && too_large) {
    RemoveLinks(links_added_this_step, /*loop_links_only=*/true, graph, &summary);
    summary.status = OptimizationStatus::kRejectedMaxError;
    summary.total_ms = total.ElapsedMs();
    return summary;
  }
  for (const auto& [id, node] : candidate.nodes()) graph->SetPose(id, node.world_from_node);
  summary.status = OptimizationStatus::kOptimized;
  summary.total_ms = total.ElapsedMs();
  return summary;
}

}  // namespace duskmap
