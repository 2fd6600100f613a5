#include "slam/graph/pose_graph.h"

#include <algorithm>
#include <Eigen/Cholesky>

#include "slam/core/check.h"

namespace duskmap {
namespace {

bool IsValidInformation(const Information6d& information) {
  if (!information.allFinite()) return false;
  if (!information.isApprox(information.transpose(), 1e-9)) return false;
  const Eigen::LLT<Information6d> llt(information);
  return llt.info() == Eigen::Success;
}

}  // namespace

void PoseGraph::AddNode(NodeId id, SessionId session, const Rigid3d& world_from_node) {
  SLAM_THROW_IF_NOT(InputError, id > 0) << "pose graph: node id must be > 0, got " << id;
  SLAM_THROW_IF_NOT(InputError, !HasNode(id)) << "pose graph: node " << id << " already exists";
  SLAM_THROW_IF_NOT(InputError, world_from_node.IsFinite())
      << "pose graph: node " << id << " has a non-finite pose";
  nodes_[id] = PoseGraphNode{id, session, world_from_node};
  incident_[id];
}

void PoseGraph::AddLink(const Link& link) {
  SLAM_THROW_IF_NOT(InputError, HasNode(link.from))
      << "pose graph: link " << link.from << "->" << link.to << " (" << LinkTypeName(link.type)
      << ") refers to missing node " << link.from;
  SLAM_THROW_IF_NOT(InputError, HasNode(link.to))
      << "pose graph: link " << link.from << "->" << link.to << " (" << LinkTypeName(link.type)
      << ") refers to missing node " << link.to;
  SLAM_THROW_IF_NOT(InputError, link.from != link.to)
      << "pose graph: link " << link.from << "->" << link.to << " links a node to itself";
  SLAM_THROW_IF_NOT(InputError, !HasLink(KeyOf(link)))
      << "pose graph: link " << link.from << "->" << link.to << " (" << LinkTypeName(link.type)
      << ") already exists";
  SLAM_THROW_IF_NOT(InputError, link.from_from_to.IsFinite())
      << "pose graph: link " << link.from << "->" << link.to << " has a non-finite transform";
  SLAM_THROW_IF_NOT(InputError, IsValidInformation(link.information))
      << "pose graph: link " << link.from << "->" << link.to
      << " information is not finite, symmetric and positive definite";
  links_[KeyOf(link)] = link;
  incident_[link.from].push_back(KeyOf(link));
  incident_[link.to].push_back(KeyOf(link));
}

bool PoseGraph::RemoveLink(const LinkKey& key) {
  if (links_.erase(key) == 0) return false;
  for (NodeId end : {key.from, key.to}) {
    std::vector<LinkKey>& keys = incident_[end];
    keys.erase(std::remove(keys.begin(), keys.end(), key), keys.end());
  }
  return true;
}

void PoseGraph::SetPose(NodeId id, const Rigid3d& world_from_node) {
  SLAM_THROW_IF_NOT(InputError, HasNode(id)) << "pose graph: no node " << id;
  SLAM_THROW_IF_NOT(InputError, world_from_node.IsFinite())
      << "pose graph: non-finite pose for node " << id;
  nodes_[id].world_from_node = world_from_node;
}

const PoseGraphNode& PoseGraph::node(NodeId id) const {
  const auto it = nodes_.find(id);
  SLAM_THROW_IF_NOT(InputError, it != nodes_.end()) << "pose graph: no node " << id;
  return it->second;
}

std::vector<LinkKey> PoseGraph::LinksOf(NodeId id) const {
  const auto it = incident_.find(id);
  return it == incident_.end() ? std::vector<LinkKey>{} : it->second;
}

std::vector<std::vector<NodeId>> PoseGraph::ConnectedComponents() const {
  std::vector<std::vector<NodeId>> components;
  std::map<NodeId, bool> visited;
  for (const auto& [id, node] : nodes_) {  // ascending ids: roots come first
    if (visited[id]) continue;
    std::vector<NodeId> component;
    std::vector<NodeId> stack = {id};
    visited[id] = true;
    while (!stack.empty()) {
      const NodeId current = stack.back();
      stack.pop_back();
      component.push_back(current);
      for (const LinkKey& key : incident_.at(current)) {
        const NodeId other = key.from == current ? key.to : key.from;
        if (!visited[other]) {
          visited[other] = true;
          stack.push_back(other);
        }
      }
    }
    std::sort(component.begin(), component.end());
    components.push_back(std::move(component));
  }
  return components;
}

}  // namespace duskmap
