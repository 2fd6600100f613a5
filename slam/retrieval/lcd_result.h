// Typed per-frame diagnostics of loop closure detection: what a user reads to
// answer "why did it not re-localize here?".
#pragma once

#include <cstddef>
#include <vector>

#include "slam/core/graph_types.h"

namespace duskmap {

enum class LcdStatus {
  kAccepted,              // 1 - P(new place) >= threshold: a loop hypothesis
  kBelowThreshold,        // score under the threshold
  kRejectedSinglePlace,   // only one candidate place (reference rule)
  kRejectedLoopRatio,     // Rtabmap/LoopRatio against the previous score
  kBadSignature,          // too few features: skipped, filter untouched
  kNoCandidates,          // no place to compare with yet (empty map, STM only)
};

const char* LcdStatusName(LcdStatus status);

struct LcdHypothesis {
  NodeId node = 0;
  double posterior = 0.0;
  float raw_likelihood = 0.0f;       // tf-idf score
  float adjusted_likelihood = 0.0f;  // normalised (§3.4)
};

struct LcdTimings {
  double quantization_ms = 0.0;
  double likelihood_ms = 0.0;
  double filter_ms = 0.0;
  double total_ms = 0.0;
};

struct LcdResult {
  LcdStatus status = LcdStatus::kNoCandidates;
  NodeId hypothesis = 0;       // argmax posterior over real places (0 when none)
  double score = 0.0;          // 1 - P(new place)
  double threshold = 0.0;      // the threshold applied this frame
  double new_place_posterior = 1.0;
  float new_place_likelihood = 0.0f;
  std::vector<LcdHypothesis> top;  // best real places by posterior
  int num_features = 0;
  int num_words = 0;           // rows quantized to an existing word (or created, mapping)
  int new_words = 0;
  int num_candidates = 0;      // places compared with
  int num_scored = 0;          // places sharing at least one word
  size_t vocabulary_words = 0;  // (bytes: Vocabulary::MemoryBytes, not per frame: it walks the index)
  LcdTimings timings;

  bool accepted() const { return status == LcdStatus::kAccepted; }
};

}  // namespace duskmap
