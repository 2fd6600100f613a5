// Incremental bag-of-words vocabulary (reference: corelib/src/VWDictionary.cpp,
// spec §2). Each node's best descriptors are quantized with the nearest-
// neighbour distance-ratio test against the existing words (and against the
// words this node created earlier); unmatched descriptors become new words.
// Words disappear when the last node referencing them is removed.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "slam/core/graph_types.h"
#include "slam/features/frame_features.h"
#include "slam/vocabulary/descriptor_index.h"
#include "slam/vocabulary/inverted_index.h"
#include "slam/vocabulary/vocabulary_snapshot.h"
#include "slam/vocabulary/word_row_source.h"
#include "slam/vocabulary/word_types.h"

namespace duskmap {

struct VocabularyOptions {
  DescriptorIndexOptions index;
  double nndr_ratio = 0.8;            // Kp/NndrRatio, on squared L2 / Hamming distances
  int max_features_per_node = 400;    // Kp/MaxFeatures: rows quantized per node (0 = all)
  double bad_signature_ratio = 0.5;   // Kp/BadSignRatio: frames with fewer than
                                      // ratio x max_features rows are not quantized
  bool new_words_compared_together = true;  // Kp/NewWordsComparedTogether

  void Check() const;
  // Rows a frame needs to be quantized (0 when max_features_per_node is 0).
  int MinFeatures() const;
};

// How Import obtained the NN index: restored from the snapshot's stored
// index, or built from the words (with the reason it was not restored).
struct IndexRestore {
  bool restored = false;
  std::string rebuild_reason;  // "" when restored or when there were no words
  double seconds = 0.0;        // time to restore or build the index
};

// The quantization of one frame.
struct NodeQuantization {
  // One entry per row considered (the first max_features_per_node rows; rows
  // are expected strongest first): the word, or kNoWord.
  std::vector<WordId> words;
  int num_features = 0;    // rows of the frame (n_j of the tf-idf score)
  int matched_words = 0;   // rows matched to a word that existed before this frame
  int new_words = 0;       // words created (AddNode) / that would be created (Quantize)
  bool bad_signature = false;  // too few rows: not quantized, skipped by LCD
  double time_ms = 0.0;

  // Distinct positive words, sorted.
  std::vector<WordId> DistinctWords() const;
};

struct NodeRemoval {
  bool was_present = false;
  std::vector<WordId> removed_words;  // words that lost their last reference, sorted
};

class Vocabulary : public WordRowSource {
 public:
  explicit Vocabulary(const VocabularyOptions& options);
  ~Vocabulary() override;

  // Mapping: quantizes `features`' descriptors, creates the new words and
  // references them from `node`. Throws InputError when the node exists or
  // the descriptor type/width differs from the vocabulary's.
  NodeQuantization AddNode(NodeId node, const FrameFeatures& features);
  NodeQuantization AddNode(NodeId node, const cv::Mat& descriptors, DescriptorKind kind);

  // Localization: the same quantization without changing anything. Matches
  // against existing words are exactly those AddNode would make; rows that
  // would create a word get kNoWord.
  NodeQuantization Quantize(const cv::Mat& descriptors, DescriptorKind kind) const;

  // Removes the node's references and deletes its orphaned words. Removing an
  // absent node (e.g. twice) returns was_present = false and changes nothing.
  NodeRemoval RemoveNode(NodeId node);

  const InvertedIndex& inverted_index() const { return inverted_; }
  bool ContainsWord(WordId word) const;
  size_t num_words() const;
  size_t num_nodes() const { return inverted_.num_nodes(); }
  int index_rebuilds() const;
  // Estimated bytes held (descriptors, NN index, inverted index).
  size_t MemoryBytes() const;
  // Rebuilds the NN index from every live word (a batch build).
  void RebuildIndex();

  // The words, the next word id and every node's references (see
  // vocabulary_snapshot.h); Import of the result restores them exactly.
  VocabularySnapshot Export() const;
  // Restores a snapshot into this vocabulary, which must be empty (no node,
  // no word, no word created yet), then restores the NN index from the
  // snapshot's index_state or, when there is none or it does not fit (other
  // options, other words, damaged), batch-builds it; index_restore() says
  // which, and the two give the same index. Throws
  // InputError naming the problem when the snapshot is inconsistent (ids not
  // increasing, a reference to a missing word, a word nobody references,
  // descriptors of the wrong type or count). The words, ids, references and
  // n_j are restored exactly; the approximate NN trees are a fresh batch
  // build, so lookups with few `checks` may differ from the exporting
  // vocabulary's incrementally grown trees (with exhaustive checks they match).
  void Import(const VocabularySnapshot& snapshot);
  const IndexRestore& index_restore() const { return index_restore_; }
  // The NN index as bytes for VocabularySnapshot::index_state (empty without
  // words or for an index kind that is not stored: LSH, hierarchical, linear).
  // Only an imported vocabulary's index is what Import would build again.
  std::vector<uint8_t> SaveIndexState() const;
  const VocabularyOptions& options() const { return options_; }

  // WordRowSource: the live words' stored rows (nullptr for an absent word;
  // kFloat32 before the first node fixed the format).
  WordRowFormat stored_row_format() const override;
  const uint8_t* FindStoredRow(WordId word) const override;

 private:
  NodeQuantization Run(const cv::Mat& descriptors, DescriptorKind kind, bool create,
                       std::vector<const uint8_t*>* new_rows) const;
  void CheckDescriptors(const cv::Mat& descriptors, DescriptorKind kind) const;

  VocabularyOptions options_;
  std::unique_ptr<DescriptorIndex> index_;  // created with the first non-empty node
  InvertedIndex inverted_;
  WordId next_word_id_ = 1;
  IndexRestore index_restore_;
};

}  // namespace duskmap
