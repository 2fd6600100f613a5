// The adjacency the retrieval module needs from the map's graph: which nodes
// are neighbours of which, and how far apart in the graph. The map/engine owns
// the real graph and mirrors its nodes and links here as it changes them.
//
// Margins follow the reference's Memory::getNeighborsId as used by the Bayes
// filter (spec §4.2): odometry and merged links add 1; loop-closure links add
// 0, so nodes of different sessions joined by a loop closure are the same
// place; proximity links are not traversed.
#pragma once

#include <cstdint>
#include <unordered_map>
#include <utility>
#include <vector>

#include "slam/core/graph_types.h"

namespace duskmap {

struct NodeMargin {
  NodeId node = 0;
  int margin = 0;  // graph distance (see above); 0 for the node itself
};

class PlaceGraph {
 public:
  // `max_margin`: neighbourhoods are cut beyond this margin (16 for the
  // reference's 18 Bayes/PredictionLC values).
  explicit PlaceGraph(int max_margin = 16);
  // Edges point at their nodes' entries: a copy would point into the
  // original; a move keeps them (the map's values keep their address).
  PlaceGraph(const PlaceGraph&) = delete;
  PlaceGraph& operator=(const PlaceGraph&) = delete;
  PlaceGraph(PlaceGraph&&) = default;
  PlaceGraph& operator=(PlaceGraph&&) = default;

  // Throws InputError if present.
  void AddNode(NodeId node, SessionId session);
  // Undirected; both nodes must exist (InputError otherwise). Adding the same
  // link twice is harmless; a self link is ignored.
  void AddLink(NodeId a, NodeId b, LinkType type);
  // Removes the node and its links; false when absent (e.g. removed twice).
  bool RemoveNode(NodeId node);

  bool Contains(NodeId node) const { return nodes_.count(node) != 0; }
  size_t size() const { return nodes_.size(); }
  SessionId Session(NodeId node) const;
  int max_margin() const { return max_margin_; }

  // Nodes within max_margin of `node` (itself included, margin 0), by
  // increasing margin then id. Cached until a link or removal nearby. Not for
  // concurrent readers (the cache and the search's scratch are shared).
  const std::vector<NodeMargin>& Neighbourhood(NodeId node) const;
  // Bumped whenever the node's neighbourhood may have changed.
  uint64_t Version(NodeId node) const;
  // Neighbours through odometry and merged links only (proximity paths).
  std::vector<NodeId> OdometryNeighbours(NodeId node) const;

 private:
  struct Entry;
  struct Edge {
    NodeId other;
    LinkType type;
    const Entry* entry;  // other's (an unordered_map's values keep their address)
  };
  struct Entry {
    NodeId id = 0;
    uint32_t index = 0;  // dense, for the search's scratch
    SessionId session = 0;
    std::vector<Edge> edges;
    mutable std::vector<NodeMargin> neighbourhood;
    mutable bool cached = false;
    uint64_t version = 0;
  };
  const Entry& At(NodeId node) const;
  std::vector<NodeMargin> Search(NodeId node) const;
  void Invalidate(const std::vector<NodeMargin>& nodes);

  int max_margin_;
  std::unordered_map<NodeId, Entry> nodes_;
  uint64_t next_version_ = 1;
  uint32_t next_index_ = 0;
  // Search's margin per Entry::index, -1 between searches (a map's first
  // frame searches every node's neighbourhood: no hashing per step).
  mutable std::vector<int> scratch_margin_;
  // Whether a neighbourhood or a version was read: until then links and
  // removals invalidate nothing (a map's links added after its nodes cost
  // no searches).
  mutable bool observed_ = false;
};

}  // namespace duskmap
