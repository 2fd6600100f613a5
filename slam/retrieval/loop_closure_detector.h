// Loop closure detection (spec §0 step 6, §2-4): quantizes each frame into
// the shared vocabulary, scores it against every place of every session
// (tf-idf), runs the Bayes filter and selects the loop hypothesis.
//
// Mapping: AddAndDetect adds the frame as a node (words, graph node, short-
// term memory) and detects. Localization over a fixed map: load the map with
// AddMapNode, then Localize each frame; Localize quantizes without creating
// words and adds no node, so the vocabulary, the inverted index and the graph
// are exactly as before the call (only the filter's posterior moves).
//
// The caller mirrors its graph's links into graph() (odometry links between
// consecutive nodes, accepted loop closures, proximity links).
#pragma once

#include <functional>
#include <deque>
#include <vector>

#include "slam/core/graph_types.h"
#include "slam/features/frame_features.h"
#include "slam/retrieval/bayes_filter.h"
#include "slam/retrieval/lcd_result.h"
#include "slam/retrieval/likelihood.h"
#include "slam/retrieval/place_graph.h"
#include "slam/vocabulary/vocabulary.h"

namespace duskmap {

struct LoopClosureOptions {
  VocabularyOptions vocabulary;
  BayesFilterOptions bayes;
  double loop_threshold = 0.11;  // Rtabmap/LoopThr, compared with 1 - P(new place)
  // RGBD/AggressiveLoopThr: used instead when the hypothesis is not yet
  // connected to the current session (see LcdQuery). 1 disables it (paper era).
  double aggressive_loop_threshold = 1.0;
  double loop_ratio = 0.0;       // Rtabmap/LoopRatio (0 = off)
  int short_term_memory_size = 10;  // Mem/STMSize: newest nodes not yet candidates
  int top_hypotheses = 5;        // hypotheses listed in the diagnostics

  void Check() const;
};

// Per-frame context supplied by the caller.
struct LcdQuery {
  // Optional: whether a node is connected to the current session's graph.
  // When given and false for the hypothesis, aggressive_loop_threshold applies.
  std::function<bool(NodeId)> connected_to_current;
};

class LoopClosureDetector {
 public:
  explicit LoopClosureDetector(const LoopClosureOptions& options);

  // Mapping: adds `node` (session `session`) and detects. The node enters the
  // short-term memory; the oldest STM node becomes a candidate place when the
  // STM is full. Throws InputError when the node exists.
  LcdResult AddAndDetect(NodeId node, SessionId session, const FrameFeatures& features,
                         const LcdQuery& query = {});
  // Localization-only: detects without adding anything to the map.
  LcdResult Localize(const FrameFeatures& features, const LcdQuery& query = {});
  // Loads a node of an existing map straight into the candidate places
  // (no detection). Its links are added through graph().
  NodeQuantization AddMapNode(NodeId node, SessionId session, const FrameFeatures& features);
  // Loads a stored map's vocabulary exactly (words, ids, references; see
  // Vocabulary::Import) instead of re-quantizing node descriptors, and makes
  // every snapshot node a candidate place of session `session_of(node)`. The
  // detector must be empty. Links are added through graph().
  void ImportMap(const VocabularySnapshot& snapshot,
                 const std::function<SessionId(NodeId)>& session_of);

  // Mapping: a new session starts; the STM becomes candidates and the filter
  // is reset (reference: triggerNewMap, spec §10).
  void StartNewSession();
  // Removes a node (graph reduction, deletion). Removing it twice returns
  // was_present = false.
  NodeRemoval RemoveNode(NodeId node);
  // Resets the filter's posterior only.
  void ResetFilter() { filter_.Reset(); }

  PlaceGraph& graph() { return graph_; }
  const PlaceGraph& graph() const { return graph_; }
  const Vocabulary& vocabulary() const { return vocabulary_; }
  const BayesFilter& filter() const { return filter_; }
  bool IsCandidate(NodeId node) const { return filter_.ContainsPlace(node); }
  // The adjusted likelihood of the last detection (for proximity ordering).
  const Likelihood& last_likelihood() const { return last_likelihood_; }
  const LoopClosureOptions& options() const { return options_; }

 private:
  LcdResult Detect(const NodeQuantization& quantization, bool query_in_index,
                   const LcdQuery& query);
  void SelectHypothesis(const LcdQuery& query, LcdResult* result);

  LoopClosureOptions options_;
  Vocabulary vocabulary_;
  PlaceGraph graph_;
  BayesFilter filter_;
  std::deque<NodeId> short_term_;
  Likelihood last_likelihood_;
  double previous_score_ = 0.0;
};

}  // namespace duskmap
