// The multi-session pose graph: nodes (id, session, world_from_node) and
// links (slam/core/graph_types.h: world_from_to = world_from_from *
// from_from_to). It validates what enters it, so that the optimiser never sees
// a non-finite pose, a dangling link or a non positive-definite information.
#pragma once

#include <map>
#include <vector>

#include "slam/core/graph_types.h"
#include "slam/core/rigid3.h"

namespace duskmap {

struct PoseGraphNode {
  NodeId id = 0;
  SessionId session = 0;
  Rigid3d world_from_node;  // in the frame of its connected component's root
};

// Identifies one link: at most one link per (from, to, type).
struct LinkKey {
  NodeId from = 0;
  NodeId to = 0;
  LinkType type = LinkType::kOdometry;
  bool operator==(const LinkKey& o) const {
    return from == o.from && to == o.to && type == o.type;
  }
  bool operator<(const LinkKey& o) const {
    if (from != o.from) return from < o.from;
    if (to != o.to) return to < o.to;
    return static_cast<int>(type) < static_cast<int>(o.type);
  }
};

inline LinkKey KeyOf(const Link& link) { return {link.from, link.to, link.type}; }

class PoseGraph {
 public:
  // Throws InputError for a duplicate id, a non-positive id or a non-finite pose.
  void AddNode(NodeId id, SessionId session, const Rigid3d& world_from_node);
  // Throws InputError when an end is missing, from == to, the (from, to, type)
  // link exists, the transform is not finite or the information is not a
  // finite symmetric positive-definite matrix.
  void AddLink(const Link& link);
  // Returns false when there is no such link.
  bool RemoveLink(const LinkKey& key);
  // Throws InputError for a missing node or a non-finite pose.
  void SetPose(NodeId id, const Rigid3d& world_from_node);

  bool HasNode(NodeId id) const { return nodes_.count(id) > 0; }
  bool HasLink(const LinkKey& key) const { return links_.count(key) > 0; }
  // Throws InputError for a missing node.
  const PoseGraphNode& node(NodeId id) const;
  const std::map<NodeId, PoseGraphNode>& nodes() const { return nodes_; }
  const std::map<LinkKey, Link>& links() const { return links_; }
  size_t num_nodes() const { return nodes_.size(); }
  size_t num_links() const { return links_.size(); }
  bool empty() const { return nodes_.empty(); }

  // Connected components through any link, each sorted by id; components are
  // ordered by their smallest (oldest) id, which is their root.
  std::vector<std::vector<NodeId>> ConnectedComponents() const;
  // Links incident to a node, as keys.
  std::vector<LinkKey> LinksOf(NodeId id) const;

 private:
  std::map<NodeId, PoseGraphNode> nodes_;
  std::map<LinkKey, Link> links_;
  std::map<NodeId, std::vector<LinkKey>> incident_;
};

}  // namespace duskmap
