// Identifiers and the link type shared by the pose graph, the map and the
// engine. Convention (as in the reference): a link from -> to with transform
// T means world_from_to = world_from_from * T, i.e. T = from_from_to maps
// coordinates in node `to`'s frame into node `from`'s frame.
#pragma once

#include <cstdint>

#include <Eigen/Core>

#include "slam/core/rigid3.h"

namespace duskmap {

using NodeId = int64_t;    // positive, increasing in creation order
using SessionId = int32_t; // 0-based, in the order sessions entered the map

enum class LinkType : int {
  kOdometry = 0,     // consecutive nodes of one session (reference: Neighbor)
  kLoopClosure = 1,  // global loop closure from LCD (reference: GlobalClosure)
  kProximity = 2,    // proximity detection in space (reference: LocalSpaceClosure)
  kMerged = 3,       // re-attached by graph reduction (reference: NeighborMerged)
  // Ties a node to the fixed root of a graph built only to check a
  // constraint (the localization's odometry cache); never stored in a map.
  kPrior = 4,
};

// "odometry", "loop_closure", ... (the names of graph_types_json.h).
const char* LinkTypeName(LinkType type);

// Information matrix order: (x, y, z, roll, pitch, yaw), as in the reference.
using Information6d = Eigen::Matrix<double, 6, 6>;

struct Link {
  NodeId from = 0;
  NodeId to = 0;
  LinkType type = LinkType::kOdometry;
  Rigid3d from_from_to;  // pose of `to` expressed in `from`'s frame
  Information6d information = Information6d::Identity();
};

}  // namespace duskmap
