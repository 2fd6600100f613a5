// Everything a map stores of its vocabulary, to restore it exactly: the
// words (ids and descriptors), the id the next new word gets, and each
// node's references (word, occurrences) with its feature count n_j.
// Produced by Vocabulary::Export, consumed by Vocabulary::Import.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <opencv2/core.hpp>

#include "slam/core/graph_types.h"
#include "slam/features/frame_features.h"
#include "slam/vocabulary/word_types.h"

namespace duskmap {

struct VocabularyNodeWords {
  NodeId node = 0;
  int num_features = 0;  // n_j: rows of the node's frame (quantized or not)
  // Distinct words of the node, increasing, with their occurrence counts (>= 1).
  std::vector<std::pair<WordId, int32_t>> word_counts;
};

struct VocabularySnapshot {
  DescriptorKind kind = DescriptorKind::kFloat;
  // How float words are stored (word_types.h, WordRowFormat); binary words
  // are exact whatever this says.
  DescriptorStorage float_storage = DescriptorStorage::kFloat32;
  std::vector<WordId> word_ids;  // strictly increasing, > 0
  // Row i: the stored row of word_ids[i]: CV_32F x cols (float32), CV_8U x
  // (8 + cols) (quantized: offset and step, then the codes) or CV_8U x cols
  // (binary).
  cv::Mat descriptors;
  WordId next_word_id = 1;       // > every word id: ids are never reused
  std::vector<VocabularyNodeWords> nodes;  // increasing node ids
  // The NN index built from these words by Import (DescriptorIndex::
  // SaveState bytes), so that Import restores it instead of building it;
  // empty when not stored. Not part of operator==.
  std::vector<uint8_t> index_state;
  // Why a stored index could not be read (e.g. its checksum failed), for the
  // rebuild notice; "" otherwise.
  std::string index_state_problem;

  WordRowFormat format() const { return WordRowFormatFor(kind, float_storage); }
  // Elements of an extracted descriptor (0 without words).
  int DescriptorCols() const;

  bool operator==(const VocabularySnapshot& other) const;
};

}  // namespace duskmap
