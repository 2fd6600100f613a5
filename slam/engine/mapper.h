// The mapping phase (spec §0, §10): input sessions are replayed back to back,
// each its own session with its own odometry frame. Per frame: features ->
// node with an odometry link to the previous node of its session -> loop
// closure detection over all nodes of all sessions and proximity detection
// around the current pose (nodes of sessions already connected to it) ->
// transform estimation on the candidates -> links -> pose-graph optimisation
// when a link was added -> graph reduction of the node leaving short-term
// memory (optional, spec §8). Loop closures between sessions merge them; the
// map ends in the frame of the oldest session each group is connected to.
// The Mapper is the only code that mutates a Map.
#pragma once

#include <deque>
#include <memory>
#include <optional>
#include <string>

#include "slam/core/rgbd_frame.h"
#include "slam/engine/engine_options.h"
#include "slam/features/feature_extractor.h"
#include "slam/map/map.h"
#include "slam/retrieval/loop_closure_detector.h"

namespace duskmap {

struct MappingTimings {
  double features_ms = 0.0;      // extraction (0 when features were given)
  double lcd_ms = 0.0;           // quantization, likelihood, Bayes filter
  double proximity_ms = 0.0;     // candidate search
  double registration_ms = 0.0;  // every transform estimation of the frame
  double optimization_ms = 0.0;
  double reduction_ms = 0.0;
  double total_ms = 0.0;
};

struct MappingFrameResult {
  NodeId node = 0;
  SessionId session = 0;
  int num_features = 0;
  LcdStatus lcd_status = LcdStatus::kNoCandidates;
  NodeId lcd_hypothesis = 0;     // 0 when none
  int registrations = 0;         // transform estimations run
  int loop_closures_added = 0;
  int proximity_links_added = 0;
  bool optimized = false;        // an optimisation ran
  OptimizationStatus optimization_status = OptimizationStatus::kEmptyGraph;
  int links_rejected = 0;        // removed by the optimiser's checks
  int nodes_reduced = 0;         // graph reduction this frame
  MappingTimings timings;
};

class Mapper {
 public:
  explicit Mapper(const EngineOptions& options);
  ~Mapper();

  // Starts a new session in the map (each input session is one).
  void StartSession(const std::string& name, const std::optional<std::string>& clock_time);
  // Extracts the frame's features and processes it.
  MappingFrameResult ProcessFrame(const RgbdFrame& frame);
  // Processes a frame whose features were already extracted with the
  // options' extractor (benchmarks, cached features).
  MappingFrameResult ProcessFrame(const RgbdFrame& frame, FrameFeatures features);

  // Flushes the short-term memory (reduction applies), stores the
  // vocabulary's words in the map, and gives the map away.
  Map Finish();
  const Map& map() const { return map_; }
  const LoopClosureDetector& loop_closure() const { return *lcd_; }
  const FeatureExtractor& extractor() const { return *extractor_; }

 private:
  struct Candidate {
    NodeId node = 0;
    LinkType type = LinkType::kLoopClosure;
  };
  void AddNode(const RgbdFrame& frame, FrameFeatures features, MappingFrameResult* result);
  std::vector<Candidate> ProximityCandidates(NodeId current, MappingFrameResult* result);
  std::optional<Link> RegisterCandidate(NodeId current, const Candidate& candidate,
                                        MappingFrameResult* result);
  void OptimizeIfLinked(const std::vector<Link>& added, MappingFrameResult* result);
  void ReduceOldestShortTerm(size_t keep, MappingFrameResult* result);
  void SnapshotWords();

  EngineOptions options_;
  RegistrationOptions registration_;
  std::unique_ptr<FeatureMatcher> matcher_;  // nullptr: registration's NNDR
  std::unique_ptr<FeatureExtractor> extractor_;
  std::unique_ptr<LoopClosureDetector> lcd_;
  Map map_;
  std::optional<SessionId> session_;
  NodeId previous_node_ = 0;  // last node of the current session (0 at a session start)
  std::string session_name_;
  FrameFeatures current_features_;  // the current frame's features, before compaction
  std::deque<NodeId> short_term_;  // nodes of the current session not yet considered for reduction
};

}  // namespace duskmap
