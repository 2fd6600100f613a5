// tf-idf likelihood of the current frame against every candidate place and
// its normalisation (reference: Memory::computeLikelihood and
// Rtabmap::adjustLikelihood, spec §3.2 and §3.4).
#pragma once

#include <functional>
#include <unordered_map>
#include <vector>

#include "slam/core/graph_types.h"
#include "slam/vocabulary/inverted_index.h"

namespace duskmap {

struct Likelihood {
  bool computed = false;     // false for skipped frames (bad signature, no candidates)
  // Raw tf-idf scores of the candidates that share a word with the frame (> 0).
  std::unordered_map<NodeId, float> raw;
  // Adjusted values that differ from 1 (candidates with raw > mean + stddev).
  std::unordered_map<NodeId, float> adjusted;
  float virtual_place = 0.0f;  // adjusted likelihood of the "new place" hypothesis
  float mean = 0.0f;           // of the raw scores > 0
  float stddev = 0.0f;         // population standard deviation of the raw scores > 0
  float max = 0.0f;            // largest raw score
  int num_candidates = 0;

  float Raw(NodeId node) const;
  // The adjusted likelihood of a candidate: 1 unless listed; 0 when not computed.
  float Adjusted(NodeId node) const;
};

// `query_words`: the distinct positive words of the current frame.
// `query_in_index`: whether the current frame's node is already in `index`
// (mapping); a lookup-only frame (localization) counts as one more node
// referencing each of its words, exactly as if it had been added.
// `is_candidate`: the places scored (the reference's WM without STM).
// `num_candidates`: how many candidates exist (for the diagnostics).
Likelihood ComputeLikelihood(const InvertedIndex& index, const std::vector<WordId>& query_words,
                             bool query_in_index,
                             const std::function<bool(NodeId)>& is_candidate, int num_candidates);

// Fills mean/stddev/max, `adjusted` and `virtual_place` from `raw` (§3.4,
// Rtabmap/VirtualPlaceLikelihoodRatio = 0).
void AdjustLikelihood(Likelihood* likelihood);

}  // namespace duskmap
