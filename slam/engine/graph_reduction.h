// Graph reduction (reference Memory::reduceNode, spec §8): a node that closed
// a loop (loop-closure or proximity link) is removed; each of its odometry
// neighbours is re-attached to the loop's other end with a merged link
// (transform L^-1 * N, the information of the weaker link). Session anchors
// (the first node of each session) are never removed. Merged links of the
// removed node are dropped, not propagated.
#pragma once

#include <vector>

#include "slam/map/map.h"

namespace duskmap {

struct ReductionResult {
  bool reduced = false;
  NodeId reduced_to = 0;             // the loop's other end with the largest id
  std::vector<Link> merged_links;    // links added (already in the map)
};

// True when `node` is the first (smallest id) node of its session.
bool IsSessionAnchor(const Map& map, NodeId node);

// Reduces `node` when it qualifies; the caller removes it from its other
// structures (vocabulary, place graph) when result.reduced.
ReductionResult ReduceNode(NodeId node, Map* map);

}  // namespace duskmap
