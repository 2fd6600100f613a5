#include "slam/engine/odometry_cache.h"

#include <algorithm>
#include <map>

#include "slam/core/check.h"
#include "slam/engine/odometry_cache_json.h"
#include "slam/graph/graph_errors.h"
#include "slam/graph/pose_graph.h"

namespace duskmap {
namespace {

Information6d DiagonalInformation(double linear_sigma, double angular_sigma) {
  Information6d information = Information6d::Zero();
  for (int i = 0; i < 3; ++i) information(i, i) = 1.0 / (linear_sigma * linear_sigma);
  for (int i = 3; i < 6; ++i) information(i, i) = 1.0 / (angular_sigma * angular_sigma);
  return information;
}

}  // namespace

void OdometryCacheOptions::Check() const {
  SLAM_THROW_IF_NOT(ConfigError, size >= 2)
      << "OdometryCacheOptions.size: must be >= 2, got " << size;
  SLAM_THROW_IF_NOT(ConfigError, max_error_ratio > 0.0)
      << "OdometryCacheOptions.max_error_ratio: must be > 0, got " << max_error_ratio;
  SLAM_THROW_IF_NOT(ConfigError, odometry_linear_sigma_m > 0.0 && odometry_angular_sigma_rad > 0.0)
      << "OdometryCacheOptions: odometry sigmas must be > 0";
  SLAM_THROW_IF_NOT(ConfigError, prior_sigma > 0.0)
      << "OdometryCacheOptions.prior_sigma: must be > 0, got " << prior_sigma;
  SLAM_THROW_IF_NOT(ConfigError, max_iterations >= 1)
      << "OdometryCacheOptions.max_iterations: must be >= 1, got " << max_iterations;
}

const char* CacheValidationName(CacheValidation validation) { return JsonEnumName(validation); }

OdometryCache::OdometryCache(const OdometryCacheOptions& options) : options_(options) {
  options_.Check();
}

void OdometryCache::AddFrame(const Rigid3d& odom_from_camera) {
  SLAM_THROW_IF_NOT(InputError, odom_from_camera.IsFinite())
      << "OdometryCache: non-finite odometry pose";
  frames_.push_back({odom_from_camera, {}});
  while (frames_.size() > static_cast<size_t>(options_.size)) frames_.pop_front();
}

size_t OdometryCache::num_localization_links() const {
  size_t n = 0;
  for (const CachedFrame& frame : frames_) n += frame.links.size();
  return n;
}

CacheValidationResult OdometryCache::Validate(NodeId node, const Rigid3d& map_from_node_camera,
                                              const Rigid3d& node_camera_from_query,
                                              const Information6d& information) {
  SLAM_THROW_IF_NOT(InputError, !frames_.empty())
      << "OdometryCache: Validate before AddFrame";
  CacheValidationResult result;
  const size_t earlier_links = num_localization_links();
  result.localization_links = static_cast<int>(earlier_links) + 1;
  const CachedLink added{node, map_from_node_camera, node_camera_from_query, information};
  if (earlier_links == 0) {
    // One localization link and a chain of frames: a tree, nothing to check.
    result.status = CacheValidation::kWaiting;
    frames_.back().links.push_back(added);
    return result;
  }
  CheckGraph check = BuildCheckGraph(added);
  if (!OptimizesWithinErrors(&check, &result)) return result;  // rejected
  result.status = CacheValidation::kApplied;
  frames_.back().links.push_back(added);
  return result;
}

OdometryCache::CheckGraph OdometryCache::BuildCheckGraph(const CachedLink& added) const {
  // Graph ids: referenced map nodes first (in id order, so the oldest is the
  // fixed root), then the cached frames in time order.
  std::map<NodeId, NodeId> graph_id_of_node;
  std::map<NodeId, Rigid3d> map_pose_of_node;
  auto reference = [&](const CachedLink& link) {
    graph_id_of_node[link.node] = 0;
    map_pose_of_node[link.node] = link.map_from_node_camera;
  };
  for (const CachedFrame& frame : frames_) {
    for (const CachedLink& link : frame.links) reference(link);
  }
  reference(added);
  NodeId next_id = 1;
  for (auto& [map_id, graph_id] : graph_id_of_node) graph_id = next_id++;
  const NodeId first_frame_id = next_id;
  const auto frame_id = [first_frame_id](size_t i) { return first_frame_id + static_cast<NodeId>(i); };

  CheckGraph check;
  PoseGraph& graph = check.graph;
  for (const auto& [map_id, graph_id] : graph_id_of_node) {
    graph.AddNode(graph_id, 0, map_pose_of_node.at(map_id));
  }
  for (size_t i = 0; i < frames_.size(); ++i) graph.AddNode(frame_id(i), 0, frames_[i].odom_from_camera);
  const NodeId root = graph_id_of_node.begin()->second;
  const Rigid3d map_from_root = map_pose_of_node.begin()->second;
  const double prior_sigma = options_.prior_sigma;
  for (const auto& [map_id, graph_id] : graph_id_of_node) {
    if (graph_id == root) continue;
    const Link prior{root, graph_id, LinkType::kPrior,
                     map_from_root.Inverse() * map_pose_of_node.at(map_id),
                     DiagonalInformation(prior_sigma, prior_sigma)};
    graph.AddLink(prior);
    check.priors.push_back(KeyOf(prior));
  }
  const Information6d odometry_information = DiagonalInformation(
      options_.odometry_linear_sigma_m, options_.odometry_angular_sigma_rad);
  for (size_t i = 0; i + 1 < frames_.size(); ++i) {
    graph.AddLink({frame_id(i), frame_id(i + 1), LinkType::kOdometry,
                   frames_[i].odom_from_camera.Inverse() * frames_[i + 1].odom_from_camera,
                   odometry_information});
  }
  for (size_t i = 0; i < frames_.size(); ++i) {
    std::vector<CachedLink> links = frames_[i].links;
    if (i + 1 == frames_.size()) links.push_back(added);
    for (const CachedLink& link : links) {
      graph.AddLink({graph_id_of_node.at(link.node), frame_id(i), LinkType::kLoopClosure,
                     link.node_camera_from_query, link.information});
    }
  }
  check.added = {graph_id_of_node.at(added.node), frame_id(frames_.size() - 1), LinkType::kLoopClosure};
  return check;
}

bool OdometryCache::OptimizesWithinErrors(CheckGraph* check, CacheValidationResult* result) const {
  PoseGraphOptimizerOptions optimizer;
  optimizer.max_iterations = options_.max_iterations;
  optimizer.max_error_ratio = 0.0;  // checked below, without the prior links
  // The check graph holds map poses and odometry poses side by side: always
  // place the frames from the links before solving.
  optimizer.initialization = PoseInitialization::kEveryOptimization;
  const OptimizationSummary summary = OptimizePoseGraph(optimizer, {check->added}, &check->graph);
  if (!summary.accepted()) return false;  // the solver failed
  for (const LinkKey& key : check->priors) check->graph.RemoveLink(key);
  const MaxGraphErrors errors = ComputeMaxGraphErrors(check->graph);
  result->max_linear_ratio = errors.linear.found ? errors.linear.ratio : 0.0;
  result->max_angular_ratio = errors.angular.found ? errors.angular.ratio : 0.0;
  return result->max_linear_ratio <= options_.max_error_ratio &&
         result->max_angular_ratio <= options_.max_error_ratio;
}

}  // namespace duskmap
