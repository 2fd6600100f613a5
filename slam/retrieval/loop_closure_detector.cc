#include "slam/retrieval/loop_closure_detector.h"

#include <algorithm>

#include "slam/core/check.h"
#include "slam/core/timer.h"
#include "slam/retrieval/lcd_result_json.h"

namespace duskmap {

const char* LcdStatusName(LcdStatus status) { return JsonEnumName(status); }

void LoopClosureOptions::Check() const {
  vocabulary.Check();
  bayes.Check();
  SLAM_THROW_IF_NOT(ConfigError, loop_threshold >= 0.0 && loop_threshold <= 1.0)
      << "LoopClosureOptions.loop_threshold must be in [0, 1], got " << loop_threshold;
  SLAM_THROW_IF_NOT(ConfigError, aggressive_loop_threshold >= 0.0 && aggressive_loop_threshold <= 1.0)
      << "LoopClosureOptions.aggressive_loop_threshold must be in [0, 1], got "
      << aggressive_loop_threshold;
  SLAM_THROW_IF_NOT(ConfigError, loop_ratio >= 0.0)
      << "LoopClosureOptions.loop_ratio must be >= 0, got " << loop_ratio;
  SLAM_THROW_IF_NOT(ConfigError, short_term_memory_size >= 0)
      << "LoopClosureOptions.short_term_memory_size must be >= 0, got " << short_term_memory_size;
  SLAM_THROW_IF_NOT(ConfigError, top_hypotheses >= 1)
      << "LoopClosureOptions.top_hypotheses must be >= 1, got " << top_hypotheses;
}

LoopClosureDetector::LoopClosureDetector(const LoopClosureOptions& options)
    : options_((options.Check(), options)),
      vocabulary_(options.vocabulary),
      graph_(options.bayes.MaxMargin()),
      filter_(options.bayes, &graph_) {}

LcdResult LoopClosureDetector::AddAndDetect(NodeId node, SessionId session,
                                            const FrameFeatures& features, const LcdQuery& query) {
  Stopwatch watch;
  SLAM_THROW_IF_NOT(InputError, node > 0) << "LoopClosureDetector: node id " << node << " must be > 0";
  SLAM_THROW_IF_NOT(InputError, !graph_.Contains(node))
      << "LoopClosureDetector: node " << node << " already exists";
  const NodeQuantization q = vocabulary_.AddNode(node, features);
  graph_.AddNode(node, session);
  short_term_.push_back(node);
  while (static_cast<int>(short_term_.size()) > options_.short_term_memory_size) {
    filter_.AddPlace(short_term_.front());
    short_term_.pop_front();
  }
  LcdResult result = Detect(q, /*query_in_index=*/true, query);
  result.timings.total_ms = watch.ElapsedMs();
  return result;
}

LcdResult LoopClosureDetector::Localize(const FrameFeatures& features, const LcdQuery& query) {
  Stopwatch watch;
  const NodeQuantization q = vocabulary_.Quantize(features.descriptors, features.kind);
  LcdResult result = Detect(q, /*query_in_index=*/false, query);
  result.timings.total_ms = watch.ElapsedMs();
  return result;
}

NodeQuantization LoopClosureDetector::AddMapNode(NodeId node, SessionId session,
                                                 const FrameFeatures& features) {
  SLAM_THROW_IF_NOT(InputError, node > 0) << "LoopClosureDetector: node id " << node << " must be > 0";
  SLAM_THROW_IF_NOT(InputError, !graph_.Contains(node))
      << "LoopClosureDetector: node " << node << " already exists";
  NodeQuantization q = vocabulary_.AddNode(node, features);
  graph_.AddNode(node, session);
  filter_.AddPlace(node);
  return q;
}

void LoopClosureDetector::ImportMap(const VocabularySnapshot& snapshot,
                                    const std::function<SessionId(NodeId)>& session_of) {
  SLAM_THROW_IF_NOT(InputError, graph_.size() == 0 && short_term_.empty())
      << "LoopClosureDetector::ImportMap: the detector already holds " << graph_.size() << " nodes";
  vocabulary_.Import(snapshot);
  for (const VocabularyNodeWords& n : snapshot.nodes) {
    graph_.AddNode(n.node, session_of(n.node));
    filter_.AddPlace(n.node);
  }
}

void LoopClosureDetector::StartNewSession() {
  for (NodeId node : short_term_) filter_.AddPlace(node);
  short_term_.clear();
  filter_.Reset();
  previous_score_ = 0.0;
}

NodeRemoval LoopClosureDetector::RemoveNode(NodeId node) {
  filter_.RemovePlace(node);
  short_term_.erase(std::remove(short_term_.begin(), short_term_.end(), node), short_term_.end());
  NodeRemoval removal = vocabulary_.RemoveNode(node);
  const bool in_graph = graph_.RemoveNode(node);
  removal.was_present = removal.was_present || in_graph;
  return removal;
}

LcdResult LoopClosureDetector::Detect(const NodeQuantization& q, bool query_in_index,
                                      const LcdQuery& query) {
  LcdResult result;
  result.timings.quantization_ms = q.time_ms;
  result.num_features = q.num_features;
  result.new_words = q.new_words;
  result.num_words = static_cast<int>(
      std::count_if(q.words.begin(), q.words.end(), [](WordId w) { return w > 0; }));
  result.num_candidates = static_cast<int>(filter_.num_places());
  result.vocabulary_words = vocabulary_.num_words();
  result.new_place_posterior = filter_.VirtualPosterior();
  last_likelihood_ = Likelihood();
  if (q.bad_signature) {
    result.status = LcdStatus::kBadSignature;
    return result;
  }
  if (filter_.num_places() == 0) {
    result.status = LcdStatus::kNoCandidates;
    return result;
  }
  Stopwatch watch;
  last_likelihood_ = ComputeLikelihood(
      vocabulary_.inverted_index(), q.DistinctWords(), query_in_index,
      [this](NodeId n) { return filter_.ContainsPlace(n); }, result.num_candidates);
  result.timings.likelihood_ms = watch.ElapsedMs();
  result.num_scored = static_cast<int>(last_likelihood_.raw.size());
  result.new_place_likelihood = last_likelihood_.virtual_place;
  watch.Restart();
  filter_.Update(last_likelihood_);
  SelectHypothesis(query, &result);
  result.timings.filter_ms = watch.ElapsedMs();
  return result;
}

// Spec §4.4: the hypothesis is the most probable real place, its score the
// total probability of the real places.
void LoopClosureDetector::SelectHypothesis(const LcdQuery& query, LcdResult* result) {
  for (const PlaceProbability& p : filter_.Top(options_.top_hypotheses)) {
    result->top.push_back({p.node, p.probability, last_likelihood_.Raw(p.node),
                           last_likelihood_.Adjusted(p.node)});
  }
  result->new_place_posterior = filter_.VirtualPosterior();
  result->score = 1.0 - filter_.VirtualPosterior();
  result->hypothesis = result->top.empty() ? 0 : result->top.front().node;
  result->threshold = options_.loop_threshold;
  if (query.connected_to_current && result->hypothesis != 0 &&
      !query.connected_to_current(result->hypothesis)) {
    result->threshold = std::min(result->threshold, options_.aggressive_loop_threshold);
  }
  const double previous = previous_score_;
  previous_score_ = result->score;
  if (result->score < result->threshold) {
    result->status = LcdStatus::kBelowThreshold;
  } else if (filter_.num_places() <= 1) {
    result->status = LcdStatus::kRejectedSinglePlace;
  } else if (options_.loop_ratio > 0.0 &&
             (previous == 0.0 || result->score < options_.loop_ratio * previous)) {
    result->status = LcdStatus::kRejectedLoopRatio;
  } else {
    result->status = LcdStatus::kAccepted;
  }
}

}  // namespace duskmap
