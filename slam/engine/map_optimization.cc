#include "slam/engine/map_optimization.h"

namespace duskmap {

PoseGraph BuildPoseGraph(const Map& map) {
  PoseGraph graph;
  for (const auto& [id, node] : map.nodes()) graph.AddNode(id, node.session, node.map_from_body);
  for (const auto& [key, link] : map.links()) graph.AddLink(link);
  return graph;
}

OptimizationSummary OptimizeMap(const PoseGraphOptimizerOptions& options,
                                const std::vector<Link>& links_added, Map* map) {
  PoseGraph graph = BuildPoseGraph(*map);
  std::vector<LinkKey> keys;
  for (const Link& link : links_added) keys.push_back(KeyOf(link));
  const OptimizationSummary summary = OptimizePoseGraph(options, keys, &graph);
  for (const LinkKey& key : summary.removed_links) map->RemoveLink(key.from, key.to);
  if (summary.accepted()) {
    for (const auto& [id, node] : graph.nodes()) {
      map->mutable_node(id).map_from_body = node.world_from_node;
    }
  }
  return summary;
}

}  // namespace duskmap
