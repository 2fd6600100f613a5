// Inverted index of the vocabulary: word -> nodes referencing it with their
// occurrence counts, and node -> its words (reference: VisualWord::references
// and Signature::words). Only nodes currently in the map hold references.
//
// Most words are referenced by one node (a word is created by the node whose
// descriptor it is, and only a revisit adds a second), so a word's list keeps
// its first reference inline and goes to the heap only from two on; the lists
// of live words are packed in one array found through WordSlots (dense while
// the vocabulary grows, packed after ShrinkToFit) instead of one hash node
// per word.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <unordered_map>
#include <vector>

#include "slam/core/graph_types.h"
#include "slam/vocabulary/word_slots.h"
#include "slam/vocabulary/word_types.h"

namespace duskmap {

struct WordReference {
  NodeId node = 0;
  int32_t count = 0;                  // occurrences of the word in the node (n_wj)
  float inverse_node_features = 0.0f; // 1 / n_j, n_j = features of the node (tf-idf term)
};

// The references of one word, in the order they were added: 24 bytes, the
// first reference inline, two or more in one heap block.
class ReferenceList {
 public:
  ReferenceList() : inline_() {}
  ~ReferenceList() { Release(); }
  ReferenceList(ReferenceList&& other) noexcept;
  ReferenceList& operator=(ReferenceList&& other) noexcept;
  ReferenceList(const ReferenceList&) = delete;
  ReferenceList& operator=(const ReferenceList&) = delete;

  const WordReference* begin() const { return data(); }
  const WordReference* end() const { return data() + size_; }
  size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  const WordReference& operator[](size_t i) const { return data()[i]; }

  void PushBack(const WordReference& reference);
  // Removes the reference of `node`, keeping the order of the others; false
  // when the node has none.
  bool Erase(NodeId node);
  // Releases the spare capacity of a heap list.
  void ShrinkToFit();
  size_t HeapBytes() const;  // heap block of two or more references, 0 when inline

 private:
  bool on_heap() const { return capacity_ > 1; }
  const WordReference* data() const { return on_heap() ? heap_ : &inline_; }
  WordReference* data() { return on_heap() ? heap_ : &inline_; }
  void Release();  // frees the heap block; back to an empty inline list
  // Takes other's references (this list must be empty and inline); other is
  // left empty.
  void TakeFrom(ReferenceList* other);

  union {
    WordReference inline_;  // capacity_ == 1
    WordReference* heap_;   // capacity_ > 1 (new[])
  };
  uint32_t size_ = 0;
  uint32_t capacity_ = 1;
};
static_assert(sizeof(ReferenceList) == 24, "one word's references take 24 bytes");

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
  size_t num_words() const { return lists_.size(); }
  // Nodes referencing `word` (empty when none); valid until the next change.
  const ReferenceList& References(WordId word) const;
  // Distinct positive words of a node, sorted (empty when absent).
  const std::vector<WordId>& NodeWords(NodeId node) const;
  int NodeFeatureCount(NodeId node) const;
  std::vector<NodeId> Nodes() const;  // sorted

  // Reserves the word table for ids up to `max_id` (an import knows it).
  void ReserveWords(WordId max_id) { word_slots_.Reserve(max_id); }
  // Releases spare capacity and packs the word table (after an import: the
  // index will not grow much).
  void ShrinkToFit();
  // Bytes held, malloc's per-block overhead and hash buckets included.
  size_t MemoryBytes() const;

 private:
  struct NodeEntry {
    std::vector<WordId> distinct_words;  // sorted
    int num_features = 0;
  };
  WordSlots word_slots_;              // word -> position in lists_
  std::vector<ReferenceList> lists_;  // live words' references
  std::vector<WordId> list_words_;    // position in lists_ -> word
  std::unordered_map<NodeId, NodeEntry> nodes_;
};

}  // namespace duskmap
