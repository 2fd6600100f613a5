#include "slam/map/map.h"

#include <numeric>

#include "slam/core/check.h"

namespace duskmap {

SessionId Map::AddSession(const std::string& name, const std::optional<std::string>& clock_time) {
  MapSession session;
  session.id = static_cast<SessionId>(sessions_.size());
  session.name = name;
  session.clock_time = clock_time;
  sessions_.push_back(session);
  return session.id;
}

void Map::CheckDescriptors(const MapNode& node) {
  const CompactFeatures& f = node.features;
  SLAM_THROW_IF_NOT(InputError, node.word_ids.size() <= f.size())
      << "Map: node " << node.id << " has more word ids than keypoints";
  SLAM_THROW_IF_NOT(InputError, node.word_counts.size() == node.word_ids.size())
      << "Map: node " << node.id << " has " << node.word_counts.size() << " word counts for "
      << node.word_ids.size() << " words";
  if (f.codes().empty()) return;
  SLAM_THROW_IF_NOT(InputError, f.storage() == metadata_.descriptor_storage)
      << "Map: node " << node.id << " keeps its descriptors as "
      << DescriptorStorageName(f.storage()) << ", the map as "
      << DescriptorStorageName(metadata_.descriptor_storage);
  if (metadata_.descriptor_cv_type < 0) {
    metadata_.descriptor_cv_type = f.descriptor_cv_type();
    metadata_.descriptor_cols = f.descriptor_cols();
    metadata_.descriptor_kind = f.kind();
  }
  SLAM_THROW_IF_NOT(InputError, f.descriptor_cv_type() == metadata_.descriptor_cv_type &&
                                    f.descriptor_cols() == metadata_.descriptor_cols &&
                                    f.kind() == metadata_.descriptor_kind)
      << "Map: node " << node.id << " descriptors (type " << f.descriptor_cv_type() << ", "
      << f.descriptor_cols() << " columns) differ from the map's (type "
      << metadata_.descriptor_cv_type << ", " << metadata_.descriptor_cols << " columns)";
}

void Map::AddNode(MapNode node) {
  SLAM_THROW_IF_NOT(InputError, node.id > last_node_id_)
      << "Map: node id " << node.id << " is not larger than the last id " << last_node_id_;
  SLAM_THROW_IF_NOT(InputError,
                    node.session >= 0 && node.session < static_cast<SessionId>(sessions_.size()))
      << "Map: node " << node.id << " refers to unknown session " << node.session;
  CheckDescriptors(node);
  last_node_id_ = node.id;
  adjacency_[node.id];
  const NodeId id = node.id;
  nodes_.emplace(id, std::move(node));
}

void Map::RemoveNode(NodeId id) {
  SLAM_CHECK(HasNode(id));
  const std::set<NodeId> neighbours = adjacency_[id];
  for (NodeId other : neighbours) RemoveLink(id, other);
  adjacency_.erase(id);
  nodes_.erase(id);
}

const MapNode& Map::node(NodeId id) const {
  auto it = nodes_.find(id);
  SLAM_CHECK_MSG(it != nodes_.end(), "unknown node " + std::to_string(id));
  return it->second;
}

MapNode& Map::mutable_node(NodeId id) {
  auto it = nodes_.find(id);
  SLAM_CHECK_MSG(it != nodes_.end(), "unknown node " + std::to_string(id));
  return it->second;
}

void Map::AddLink(const Link& link) {
  SLAM_THROW_IF_NOT(InputError, link.from != link.to && HasNode(link.from) && HasNode(link.to))
      << "Map: link " << link.from << " -> " << link.to << " needs two distinct existing nodes";
  SLAM_THROW_IF_NOT(InputError, !HasLink(link.from, link.to))
      << "Map: nodes " << link.from << " and " << link.to << " are already linked";
  SLAM_THROW_IF_NOT(InputError, link.from_from_to.IsFinite() && link.information.allFinite())
      << "Map: link " << link.from << " -> " << link.to << " is not finite";
  links_.emplace(std::make_pair(link.from, link.to), link);
  adjacency_[link.from].insert(link.to);
  adjacency_[link.to].insert(link.from);
}

bool Map::HasLink(NodeId a, NodeId b) const {
  auto it = adjacency_.find(a);
  return it != adjacency_.end() && it->second.count(b) > 0;
}

bool Map::RemoveLink(NodeId a, NodeId b) {
  if (!HasLink(a, b)) return false;
  if (links_.erase({a, b}) == 0) links_.erase({b, a});
  adjacency_[a].erase(b);
  adjacency_[b].erase(a);
  return true;
}

std::vector<Link> Map::LinksOf(NodeId id) const {
  std::vector<Link> result;
  auto it = adjacency_.find(id);
  if (it == adjacency_.end()) return result;
  for (NodeId other : it->second) {
    auto forward = links_.find({id, other});
    result.push_back(forward != links_.end() ? forward->second : links_.at({other, id}));
  }
  return result;
}

std::vector<NodeId> Map::NodesOfSession(SessionId session) const {
  std::vector<NodeId> ids;
  for (const auto& [id, node] : nodes_) {
    if (node.session == session) ids.push_back(id);
  }
  return ids;
}

std::vector<std::vector<SessionId>> Map::ConnectedSessionGroups() const {
  std::vector<SessionId> parent(sessions_.size());
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&parent](SessionId s) {
    while (parent[s] != s) s = parent[s] = parent[parent[s]];
    return s;
  };
  for (const auto& [key, link] : links_) {
    const SessionId a = find(node(link.from).session);
    const SessionId b = find(node(link.to).session);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
  std::map<SessionId, std::vector<SessionId>> groups;
  for (SessionId s = 0; s < static_cast<SessionId>(sessions_.size()); ++s) {
    groups[find(s)].push_back(s);
  }
  std::vector<std::vector<SessionId>> result;
  for (auto& [root, members] : groups) result.push_back(std::move(members));
  return result;
}

void Map::SetWords(MapWords words) {
  SLAM_THROW_IF_NOT(InputError, static_cast<int>(words.ids.size()) == words.descriptors.rows)
      << "Map: " << words.ids.size() << " word ids but " << words.descriptors.rows
      << " word descriptors";
  for (size_t i = 1; i < words.ids.size(); ++i) {
    SLAM_THROW_IF_NOT(InputError, words.ids[i] > words.ids[i - 1])
        << "Map: word ids must increase (" << words.ids[i - 1] << " then " << words.ids[i] << ")";
  }
  words_ = std::move(words);
}

}  // namespace duskmap
