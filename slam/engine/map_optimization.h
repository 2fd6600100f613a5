// Pose-graph optimisation of a Map (spec §7): the map's nodes and links are
// copied into a PoseGraph, optimised by slam/graph (oldest node of each
// connected component fixed, max-error check), and the result is written
// back: new poses when accepted, and the links the optimiser rejected are
// removed from the map.
#pragma once

#include <vector>

#include "slam/graph/pose_graph.h"
#include "slam/graph/pose_graph_optimizer.h"
#include "slam/map/map.h"

namespace duskmap {

PoseGraph BuildPoseGraph(const Map& map);

// `links_added`: links of `map` added since the last optimisation.
OptimizationSummary OptimizeMap(const PoseGraphOptimizerOptions& options,
                                const std::vector<Link>& links_added, Map* map);

}  // namespace duskmap
