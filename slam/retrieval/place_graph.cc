#include "slam/retrieval/place_graph.h"

#include <algorithm>
#include <deque>

#include "slam/core/check.h"

namespace duskmap {
namespace {
// -1: not traversed; otherwise the margin the link adds.
int LinkCost(LinkType type) {
  switch (type) {
    case LinkType::kOdometry:
    case LinkType::kMerged: return 1;
    case LinkType::kLoopClosure: return 0;
    case LinkType::kProximity:
    case LinkType::kPrior: return -1;  // priors exist only in check graphs, never here
  }
  return -1;
}
}  // namespace

PlaceGraph::PlaceGraph(int max_margin) : max_margin_(max_margin) {
  SLAM_THROW_IF_NOT(ConfigError, max_margin >= 0)
      << "PlaceGraph: max_margin must be >= 0, got " << max_margin;
}

const PlaceGraph::Entry& PlaceGraph::At(NodeId node) const {
  auto it = nodes_.find(node);
  SLAM_THROW_IF_NOT(InputError, it != nodes_.end()) << "PlaceGraph: unknown node " << node;
  return it->second;
}

void PlaceGraph::AddNode(NodeId node, SessionId session) {
  SLAM_THROW_IF_NOT(InputError, !Contains(node)) << "PlaceGraph: node " << node << " already added";
  Entry entry;
  entry.id = node;
  entry.index = next_index_++;
  entry.session = session;
  entry.version = next_version_++;
  nodes_.emplace(node, std::move(entry));
}

void PlaceGraph::AddLink(NodeId a, NodeId b, LinkType type) {
  At(a);
  At(b);
  if (a == b) return;
  auto& edges_a = nodes_.at(a).edges;
  const bool exists = std::any_of(edges_a.begin(), edges_a.end(), [&](const Edge& e) {
    return e.other == b && e.type == type;
  });
  if (exists) return;
  Entry& entry_b = nodes_.at(b);
  edges_a.push_back({b, type, &entry_b});
  entry_b.edges.push_back({a, type, &nodes_.at(a)});
  if (LinkCost(type) < 0) return;  // proximity links change no neighbourhood
  // Nothing has read a neighbourhood or a version yet (a map's links being
  // added after its nodes): nothing cached can be stale.
  if (!observed_) return;
  // Every node whose neighbourhood can change is within max_margin of a or b
  // in the new graph (margins are symmetric).
  Invalidate(Search(a));
  Invalidate(Search(b));
}

bool PlaceGraph::RemoveNode(NodeId node) {
  auto it = nodes_.find(node);
  if (it == nodes_.end()) return false;
  if (observed_) Invalidate(Search(node));
  for (const Edge& e : it->second.edges) {
    auto& other = nodes_.at(e.other).edges;
    other.erase(std::remove_if(other.begin(), other.end(),
                               [node](const Edge& x) { return x.other == node; }),
                other.end());
  }
  nodes_.erase(node);
  return true;
}

SessionId PlaceGraph::Session(NodeId node) const { return At(node).session; }

uint64_t PlaceGraph::Version(NodeId node) const {
  observed_ = true;
  return At(node).version;
}

void PlaceGraph::Invalidate(const std::vector<NodeMargin>& nodes) {
  for (const NodeMargin& m : nodes) {
    Entry& e = nodes_.at(m.node);
    e.cached = false;
    e.neighbourhood.clear();
    e.version = next_version_++;
  }
}

// 0-1 breadth-first search (loop-closure links cost 0, odometry links 1).
std::vector<NodeMargin> PlaceGraph::Search(NodeId start) const {
  const Entry& first = At(start);
  if (scratch_margin_.size() < next_index_) scratch_margin_.resize(next_index_, -1);
  std::vector<const Entry*> reached{&first};
  scratch_margin_[first.index] = 0;
  std::deque<const Entry*> queue{&first};
  while (!queue.empty()) {
    const Entry* n = queue.front();
    queue.pop_front();
    const int m = scratch_margin_[n->index];
    for (const Edge& e : n->edges) {
      const int cost = LinkCost(e.type);
      if (cost < 0 || m + cost > max_margin_) continue;
      int& known = scratch_margin_[e.entry->index];
      if (known >= 0 && known <= m + cost) continue;
      if (known < 0) reached.push_back(e.entry);
      known = m + cost;
      if (cost == 0) {
        queue.push_front(e.entry);
      } else {
        queue.push_back(e.entry);
      }
    }
  }
  std::vector<NodeMargin> out;
  out.reserve(reached.size());
  for (const Entry* e : reached) {
    out.push_back({e->id, scratch_margin_[e->index]});
    scratch_margin_[e->index] = -1;
  }
  std::sort(out.begin(), out.end(), [](const NodeMargin& x, const NodeMargin& y) {
    return x.margin != y.margin ? x.margin < y.margin : x.node < y.node;
  });
  return out;
}

const std::vector<NodeMargin>& PlaceGraph::Neighbourhood(NodeId node) const {
  observed_ = true;
  const Entry& e = At(node);
  if (!e.cached) {
    e.neighbourhood = Search(node);
    e.cached = true;
  }
  return e.neighbourhood;
}

std::vector<NodeId> PlaceGraph::OdometryNeighbours(NodeId node) const {
  std::vector<NodeId> out;
  for (const Edge& e : At(node).edges) {
    if (e.type == LinkType::kOdometry || e.type == LinkType::kMerged) out.push_back(e.other);
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

}  // namespace duskmap
