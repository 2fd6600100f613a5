// Proximity detection in space (reference: Rtabmap::process "Proximity
// detections", spec §5): places near the current pose estimate, grouped into
// paths (one per session and pass), ordered by visual likelihood so that the
// node recorded under the most similar light is tried first.
#pragma once

#include <functional>
#include <vector>

#include <Eigen/Core>

#include "slam/core/graph_types.h"
#include "slam/core/rigid3.h"
#include "slam/retrieval/place_graph.h"

namespace duskmap {

struct ProximityOptions {
  double local_radius_m = 1.0;            // RGBD/LocalRadius (paper: 1 m; reference default 10)
  double max_angle_deg = 45.0;            // RGBD/ProximityAngle: heading window
  int max_paths = 3;                      // RGBD/ProximityMaxPaths (3 mapping, 1 localization; 0 = all)
  double path_filtering_radius_m = 1.0;   // RGBD/ProximityPathFilteringRadius
  int max_path_depth = 50;                // RGBD/ProximityMaxGraphDepth, odometry hops in a path
  // The "forward" axis of a node / camera frame, compared for the heading
  // window (the reference compares base x axes; duskmap poses are cameras, z forward).
  Eigen::Vector3d forward_axis = Eigen::Vector3d::UnitZ();

  void Check() const;
};

struct ProximityNode {
  NodeId node = 0;
  Rigid3d world_from_node;
};

struct ProximityCandidate {
  NodeId node = 0;              // the node to register against
  double distance_m = 0.0;      // to the current pose estimate
  float likelihood = 0.0f;      // adjusted LCD likelihood (0 when not computed)
  std::vector<NodeId> path;     // the path the node was chosen from, sorted
};

struct ProximityResult {
  std::vector<ProximityCandidate> candidates;  // in the order to try, <= max_paths
  int num_in_radius = 0;        // nodes within local_radius_m
  int num_paths = 0;            // paths they form
  int num_skipped = 0;          // paths skipped (already linked, too far, none in heading window)
  double time_ms = 0.0;
};

// `nodes`: the candidate places with their poses (the caller leaves out the
// short-term memory and the current node). `graph` gives the odometry links
// that form paths. `likelihood(node)`: the adjusted LCD likelihood (0 for
// all when LCD did not run). `already_linked(node)`, optional: nodes to skip.
ProximityResult FindProximityCandidates(const ProximityOptions& options,
                                        const Rigid3d& world_from_camera,
                                        const std::vector<ProximityNode>& nodes,
                                        const PlaceGraph& graph,
                                        const std::function<float(NodeId)>& likelihood,
                                        const std::function<bool(NodeId)>& already_linked = {});

}  // namespace duskmap
