#include "slam/retrieval/proximity.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <tuple>
#include <unordered_map>

#include "slam/core/check.h"
#include "slam/core/timer.h"

namespace duskmap {
namespace {

struct Near {
  NodeId node;
  double distance_m;
  double angle_rad;  // between forward axes
};

// Spec §5.2: repeatedly take the nearest remaining node and collect what its
// odometry links reach within the set (depth <= max_depth).
std::vector<std::vector<Near>> SegmentIntoPaths(std::vector<Near> nearby, const PlaceGraph& graph,
                                                int max_depth) {
  std::sort(nearby.begin(), nearby.end(), [](const Near& a, const Near& b) {
    return a.distance_m != b.distance_m ? a.distance_m < b.distance_m : a.node < b.node;
  });
  std::unordered_map<NodeId, size_t> position;
  for (size_t i = 0; i < nearby.size(); ++i) position[nearby[i].node] = i;
  std::vector<bool> used(nearby.size(), false);
  std::vector<std::vector<Near>> paths;
  for (size_t seed = 0; seed < nearby.size(); ++seed) {
    if (used[seed]) continue;
    std::vector<Near> path;
    std::deque<std::pair<size_t, int>> queue{{seed, 0}};
    used[seed] = true;
    while (!queue.empty()) {
      const auto [i, depth] = queue.front();
      queue.pop_front();
      path.push_back(nearby[i]);
      if (depth >= max_depth || !graph.Contains(nearby[i].node)) continue;
      for (NodeId n : graph.OdometryNeighbours(nearby[i].node)) {
        auto it = position.find(n);
        if (it == position.end() || used[it->second]) continue;
        used[it->second] = true;
        queue.push_back({it->second, depth + 1});
      }
    }
    paths.push_back(std::move(path));
  }
  return paths;
}

}  // namespace

void ProximityOptions::Check() const {
  SLAM_THROW_IF_NOT(ConfigError, local_radius_m > 0.0)
      << "ProximityOptions.local_radius_m must be > 0, got " << local_radius_m;
  SLAM_THROW_IF_NOT(ConfigError, max_angle_deg > 0.0 && max_angle_deg <= 180.0)
      << "ProximityOptions.max_angle_deg must be in (0, 180], got " << max_angle_deg;
  SLAM_THROW_IF_NOT(ConfigError, max_paths >= 0)
      << "ProximityOptions.max_paths must be >= 0, got " << max_paths;
  SLAM_THROW_IF_NOT(ConfigError, path_filtering_radius_m > 0.0)
      << "ProximityOptions.path_filtering_radius_m must be > 0, got " << path_filtering_radius_m;
  SLAM_THROW_IF_NOT(ConfigError, max_path_depth >= 0)
      << "ProximityOptions.max_path_depth must be >= 0, got " << max_path_depth;
  SLAM_THROW_IF_NOT(ConfigError, forward_axis.allFinite() && forward_axis.norm() > 0.0)
      << "ProximityOptions.forward_axis must be a finite non-zero vector";
}

ProximityResult FindProximityCandidates(const ProximityOptions& options,
                                        const Rigid3d& world_from_camera,
                                        const std::vector<ProximityNode>& nodes,
                                        const PlaceGraph& graph,
                                        const std::function<float(NodeId)>& likelihood,
                                        const std::function<bool(NodeId)>& already_linked) {
  Stopwatch watch;
  options.Check();
  SLAM_THROW_IF_NOT(InputError, world_from_camera.IsFinite())
      << "FindProximityCandidates: the current pose estimate is not finite";
  const Eigen::Vector3d axis = options.forward_axis.normalized();
  const Eigen::Vector3d forward = world_from_camera.rotation * axis;
  std::vector<Near> nearby;
  for (const ProximityNode& n : nodes) {
    const double d = (n.world_from_node.translation - world_from_camera.translation).norm();
    if (!(d <= options.local_radius_m)) continue;
    const double cos_angle = std::clamp((n.world_from_node.rotation * axis).dot(forward), -1.0, 1.0);
    nearby.push_back({n.node, d, std::acos(cos_angle)});
  }
  ProximityResult result;
  result.num_in_radius = static_cast<int>(nearby.size());
  std::vector<std::vector<Near>> paths = SegmentIntoPaths(nearby, graph, options.max_path_depth);
  result.num_paths = static_cast<int>(paths.size());

  // Spec §5.3: a path's key is its best-likelihood node (ties: nearer), then
  // (likelihood desc, distance asc, id desc).
  struct Keyed {
    float likelihood;
    Near best;
    size_t path;
  };
  std::vector<Keyed> keyed;
  for (size_t p = 0; p < paths.size(); ++p) {
    Keyed k{-1.0f, {}, p};
    for (const Near& n : paths[p]) {
      const float l = likelihood ? likelihood(n.node) : 0.0f;
      if (l > k.likelihood || (l == k.likelihood && n.distance_m < k.best.distance_m)) {
        k.likelihood = l;
        k.best = n;
      }
    }
    keyed.push_back(k);
  }
  std::sort(keyed.begin(), keyed.end(), [](const Keyed& a, const Keyed& b) {
    return std::make_tuple(-a.likelihood, a.best.distance_m, -a.best.node) <
           std::make_tuple(-b.likelihood, b.best.distance_m, -b.best.node);
  });

  const double max_angle_rad = options.max_angle_deg * M_PI / 180.0;
  auto in_window = [&](const Near& n) {
    return n.distance_m <= options.local_radius_m && n.angle_rad <= max_angle_rad;
  };
  for (const Keyed& k : keyed) {
    if (options.max_paths > 0 && static_cast<int>(result.candidates.size()) >= options.max_paths) break;
    const std::vector<Near>& path = paths[k.path];
    const Near* target = nullptr;
    if (k.likelihood > 0.0f && in_window(k.best)) {
      target = &k.best;
    } else {
      for (const Near& n : path) {  // nearest in the window
        if (in_window(n) && (target == nullptr || n.distance_m < target->distance_m)) target = &n;
      }
    }
    if (target == nullptr || target->distance_m > options.path_filtering_radius_m ||
        (already_linked && already_linked(target->node))) {
      ++result.num_skipped;
      continue;
    }
    ProximityCandidate c;
    c.node = target->node;
    c.distance_m = target->distance_m;
    c.likelihood = likelihood ? likelihood(target->node) : 0.0f;
    for (const Near& n : path) c.path.push_back(n.node);
    std::sort(c.path.begin(), c.path.end());
    result.candidates.push_back(std::move(c));
  }
  result.time_ms = watch.ElapsedMs();
  return result;
}

}  // namespace duskmap
