// Inverted index of the vocabulary: word -> nodes referencing it with their
// occurrence counts, and node -> its words (reference: VisualWord::references
// and Signature::words). Only nodes currently in the map hold references.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <unordered_map>
#include <vector>

#include "slam/core/graph_types.h"
#include "slam/vocabulary/word_types.h"

namespace duskmap {

struct WordReference {
  NodeId node = 0;
  int32_t count = 0;                  // occurrences of the word in the node (n_wj)
  float inverse_node_features = 0.0f; // 1 / n_j, n_j = features of the node (tf-idf term)
};

class InvertedIndex {
 public:
  // Registers `node` with its quantized words (kNoWord entries are ignored)
  // and its total feature count n_j (non-quantized features included, as the
  // reference's Memory::getNi). Throws InputError if the node is present.
  void AddNode(NodeId node, const std::vector<WordId>& words, int num_features);

  // Drops every reference of `node`. Returns the words left without any
  // reference (sorted), or nullopt when the node is not present.
  std::optional<std::vector<WordId>> RemoveNode(NodeId node);

  bool ContainsNode(NodeId node) const { return nodes_.count(node) != 0; }
  size_t num_nodes() const { return nodes_.size(); }
  size_t num_words() const { return refs_.size(); }
  // Nodes referencing `word` (empty when none).
  const std::vector<WordReference>& References(WordId word) const;
  // Distinct positive words of a node, sorted (empty when absent).
  const std::vector<WordId>& NodeWords(NodeId node) const;
  int NodeFeatureCount(NodeId node) const;
  std::vector<NodeId> Nodes() const;  // sorted

  size_t MemoryBytes() const;

 private:
  struct NodeEntry {
    std::vector<WordId> distinct_words;  // sorted
    int num_features = 0;
  };
  std::unordered_map<WordId, std::vector<WordReference>> refs_;
  std::unordered_map<NodeId, NodeEntry> nodes_;
};

}  // namespace duskmap
