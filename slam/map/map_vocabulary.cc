#include "slam/map/map_vocabulary.h"

#include <set>
#include <string>

#include "slam/core/check.h"

namespace duskmap {

VocabularySnapshot MapVocabularySnapshot(const Map& map) {
  return MapVocabularySnapshot(map, map.words());
}

VocabularySnapshot MapVocabularySnapshot(const Map& map, const MapWords& words) {
  VocabularySnapshot snapshot;
  snapshot.kind = map.metadata().descriptor_kind;
  snapshot.float_storage = map.metadata().word_storage;
  snapshot.word_ids = words.ids;
  snapshot.descriptors = words.descriptors;
  snapshot.next_word_id = words.next_word_id;
  snapshot.index_state = words.index_state;
  snapshot.index_state_problem = words.index_problem;
  for (const auto& [id, node] : map.nodes()) {
    SLAM_THROW_IF_NOT(InputError, node.word_counts.size() == node.word_ids.size())
        << "map vocabulary: node " << id << " has " << node.word_counts.size()
        << " word counts for " << node.word_ids.size() << " words";
    VocabularyNodeWords n;
    n.node = id;
    n.num_features = node.vocabulary_features;
    for (size_t i = 0; i < node.word_ids.size(); ++i) {
      n.word_counts.push_back({node.word_ids[i], node.word_counts[i]});
    }
    snapshot.nodes.push_back(std::move(n));
  }
  return snapshot;
}

void SetMapVocabulary(const VocabularySnapshot& snapshot, Map* map) {
  SLAM_CHECK(map != nullptr);
  const MapMetadata& m = map->metadata();
  SLAM_THROW_IF_NOT(InputError,
                    snapshot.word_ids.empty() ||
                        snapshot.format() == WordRowFormatFor(m.descriptor_kind, m.word_storage))
      << "map vocabulary: the words are stored as "
      << DescriptorStorageName(snapshot.float_storage) << ", the map records "
      << DescriptorStorageName(m.word_storage);
  std::set<NodeId> listed;
  for (const VocabularyNodeWords& n : snapshot.nodes) {
    SLAM_THROW_IF_NOT(InputError, map->HasNode(n.node))
        << "map vocabulary: the vocabulary references node " << n.node
        << ", which the map does not have";
    MapNode& node = map->mutable_node(n.node);
    node.word_ids.clear();
    node.word_counts.clear();
    for (const auto& [word, count] : n.word_counts) {
      node.word_ids.push_back(word);
      node.word_counts.push_back(count);
    }
    node.vocabulary_features = n.num_features;
    listed.insert(n.node);
  }
  for (const auto& [id, node] : map->nodes()) {
    if (listed.count(id)) continue;
    MapNode& unlisted = map->mutable_node(id);
    unlisted.word_ids.clear();
    unlisted.word_counts.clear();
    unlisted.vocabulary_features = 0;
  }
  MapWords words;
  words.ids = snapshot.word_ids;
  words.descriptors = snapshot.descriptors;
  words.next_word_id = snapshot.next_word_id;
  map->SetWords(std::move(words));
}

}  // namespace duskmap
