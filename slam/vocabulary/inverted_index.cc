#include "slam/vocabulary/inverted_index.h"

#include <algorithm>
#include <map>

#include "slam/core/check.h"

namespace duskmap {
namespace {
const std::vector<WordReference> kNoReferences;
const std::vector<WordId> kNoWords;
}  // namespace

void InvertedIndex::AddNode(NodeId node, const std::vector<WordId>& words, int num_features) {
  SLAM_THROW_IF_NOT(InputError, !ContainsNode(node))
      << "InvertedIndex: node " << node << " is already in the vocabulary";
  SLAM_THROW_IF_NOT(InputError, num_features >= 0)
      << "InvertedIndex: node " << node << " has a negative feature count";
  std::map<WordId, int32_t> counts;
  for (WordId w : words) {
    if (w > 0) ++counts[w];
  }
  NodeEntry entry;
  entry.num_features = std::max<int>(num_features, static_cast<int>(words.size()));
  const float inverse = entry.num_features > 0 ? 1.0f / entry.num_features : 0.0f;
  entry.distinct_words.reserve(counts.size());
  for (const auto& [word, count] : counts) {
    entry.distinct_words.push_back(word);
    refs_[word].push_back({node, count, inverse});
  }
  nodes_.emplace(node, std::move(entry));
}

std::optional<std::vector<WordId>> InvertedIndex::RemoveNode(NodeId node) {
  auto it = nodes_.find(node);
  if (it == nodes_.end()) return std::nullopt;
  std::vector<WordId> orphaned;
  for (WordId w : it->second.distinct_words) {
    auto refs = refs_.find(w);
    SLAM_CHECK(refs != refs_.end());
    auto& list = refs->second;
    auto pos = std::find_if(list.begin(), list.end(),
                            [node](const WordReference& r) { return r.node == node; });
    SLAM_CHECK(pos != list.end());
    list.erase(pos);
    if (list.empty()) {
      refs_.erase(refs);
      orphaned.push_back(w);
    }
  }
  nodes_.erase(it);
  return orphaned;  // distinct_words was sorted, so is this
}

const std::vector<WordReference>& InvertedIndex::References(WordId word) const {
  auto it = refs_.find(word);
  return it == refs_.end() ? kNoReferences : it->second;
}

const std::vector<WordId>& InvertedIndex::NodeWords(NodeId node) const {
  auto it = nodes_.find(node);
  return it == nodes_.end() ? kNoWords : it->second.distinct_words;
}

int InvertedIndex::NodeFeatureCount(NodeId node) const {
  auto it = nodes_.find(node);
  return it == nodes_.end() ? 0 : it->second.num_features;
}

std::vector<NodeId> InvertedIndex::Nodes() const {
  std::vector<NodeId> ids;
  ids.reserve(nodes_.size());
  for (const auto& [id, entry] : nodes_) ids.push_back(id);
  std::sort(ids.begin(), ids.end());
  return ids;
}

size_t InvertedIndex::MemoryBytes() const {
  // Hash nodes (~ key + value + next pointer + bucket) and vector payloads.
  size_t bytes = refs_.bucket_count() * sizeof(void*) + nodes_.bucket_count() * sizeof(void*);
  for (const auto& [w, list] : refs_) {
    bytes += sizeof(w) + sizeof(list) + sizeof(void*) + list.capacity() * sizeof(WordReference);
  }
  for (const auto& [n, entry] : nodes_) {
    bytes += sizeof(n) + sizeof(entry) + sizeof(void*) +
             entry.distinct_words.capacity() * sizeof(WordId);
  }
  return bytes;
}

}  // namespace duskmap
