#include "slam/engine/graph_reduction.h"

#include "slam/core/check.h"

namespace duskmap {
namespace {

bool IsLoopType(LinkType type) {
  return type == LinkType::kLoopClosure || type == LinkType::kProximity;
}

// The link's other end and its transform seen from `node` (node_from_other).
struct IncidentLink {
  NodeId other = 0;
  Rigid3d node_from_other;
  Link link;
};

std::vector<IncidentLink> Incident(const Map& map, NodeId node) {
  std::vector<IncidentLink> result;
  for (const Link& link : map.LinksOf(node)) {
    IncidentLink incident;
    incident.link = link;
    if (link.from == node) {
      incident.other = link.to;
      incident.node_from_other = link.from_from_to;
    } else {
      incident.other = link.from;
      incident.node_from_other = link.from_from_to.Inverse();
    }
    result.push_back(incident);
  }
  return result;
}

}  // namespace

bool IsSessionAnchor(const Map& map, NodeId node) {
  const SessionId session = map.node(node).session;
  for (const auto& [id, n] : map.nodes()) {
    if (n.session == session) return id == node;  // nodes are in id order
  }
  return false;
}

ReductionResult ReduceNode(NodeId node, Map* map) {
  ReductionResult result;
  if (IsSessionAnchor(*map, node)) return result;
  const std::vector<IncidentLink> incident = Incident(*map, node);
  for (const IncidentLink& l : incident) {
    if (IsLoopType(l.link.type)) result.reduced_to = std::max(result.reduced_to, l.other);
  }
  if (result.reduced_to == 0) return result;
  for (const IncidentLink& loop : incident) {
    if (!IsLoopType(loop.link.type)) continue;  // odometry: source of N; merged: dropped
    for (const IncidentLink& neighbour : incident) {
      if (neighbour.link.type != LinkType::kOdometry) continue;
      const NodeId x = loop.other, n = neighbour.other;
      if (x == n || map->HasLink(x, n)) continue;
      Link merged;
      merged.from = x;
      merged.to = n;
      merged.type = LinkType::kMerged;
      merged.from_from_to = loop.node_from_other.Inverse() * neighbour.node_from_other;
      // A merged link chains the loop and the odometry link: their
      // covariances add (spec §8, NeighborMerged).
      const Eigen::Matrix<double, 6, 6> covariance =
          loop.link.information.inverse() + neighbour.link.information.inverse();
      merged.information = covariance.inverse();
      map->AddLink(merged);
      result.merged_links.push_back(merged);
    }
  }
  map->RemoveNode(node);
  result.reduced = true;
  return result;
}

}  // namespace duskmap
