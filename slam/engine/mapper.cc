#include "slam/engine/mapper.h"

#include <algorithm>
#include <set>

#include "slam/core/check.h"
#include "slam/core/timer.h"
#include "slam/features/feature_factory.h"
#include "slam/features/feature_options_json.h"
#include "slam/engine/graph_reduction.h"
#include "slam/engine/map_optimization.h"
#include "slam/map/map_vocabulary.h"
#include "slam/retrieval/proximity.h"

namespace duskmap {
namespace {

Information6d OdometryInformation(const OdometryNoiseOptions& o) {
  Information6d information = Information6d::Zero();
  for (int i = 0; i < 3; ++i) information(i, i) = 1.0 / (o.linear_sigma_m * o.linear_sigma_m);
  for (int i = 3; i < 6; ++i) {
    information(i, i) = 1.0 / (o.angular_sigma_rad * o.angular_sigma_rad);
  }
  return information;
}

bool IsIdentity(const Rigid3d& pose) {
  return pose.translation.squaredNorm() == 0.0 &&
         pose.rotation.coeffs() == Eigen::Quaterniond::Identity().coeffs();
}

}  // namespace

Mapper::Mapper(const EngineOptions& options)
    : options_(options), registration_(options.Registration()) {
  options_.Check();
  extractor_ = CreateFeatureExtractor(options_.features);
  matcher_ = CreateFeatureMatcher(options_.matcher);
  lcd_ = std::make_unique<LoopClosureDetector>(options_.LoopClosure());
  MapMetadata metadata;
  metadata.feature_type = options_.features.type;
  metadata.feature_parameters_json = ToJsonObject(options_.features).dump();
  metadata.engine_parameters_json = EngineOptionsToJson(options_).dump();
  metadata.descriptor_kind = extractor_->kind();
  metadata.descriptor_storage = options_.mapping.descriptor_storage;
  metadata.word_storage = options_.loop_closure.vocabulary.index.float_storage;
  map_ = Map(metadata);
}

Mapper::~Mapper() = default;

void Mapper::StartSession(const std::string& name, const std::optional<std::string>& clock_time) {
  MappingFrameResult ignored;
  ReduceOldestShortTerm(0, &ignored);
  session_ = map_.AddSession(name, clock_time);
  session_name_ = name;
  previous_node_ = 0;
  lcd_->StartNewSession();
}

MappingFrameResult Mapper::ProcessFrame(const RgbdFrame& frame) {
  Stopwatch watch;
  FrameFeatures features = extractor_->ExtractFrame(frame);
  const double features_ms = watch.ElapsedMs();
  MappingFrameResult result = ProcessFrame(frame, std::move(features));
  result.timings.features_ms = features_ms;
  result.timings.total_ms += features_ms;
  return result;
}

MappingFrameResult Mapper::ProcessFrame(const RgbdFrame& frame, FrameFeatures features) {
  SLAM_THROW_IF_NOT(InputError, session_.has_value())
      << "Mapper: frame " << frame.frame_index << " before any StartSession";
  // Odometry reset (identity after non-identity) starts a new session (spec §0.1).
  if (previous_node_ != 0 && IsIdentity(frame.odom_from_body) &&
      !IsIdentity(map_.node(previous_node_).odom_from_body)) {
    StartSession(session_name_ + "+reset", map_.sessions().back().clock_time);
  }
  Stopwatch total;
  MappingFrameResult result;
  AddNode(frame, std::move(features), &result);
  const NodeId current = result.node;

  std::vector<Candidate> candidates;
  if (result.lcd_status == LcdStatus::kAccepted) {
    candidates.push_back({result.lcd_hypothesis, LinkType::kLoopClosure});
  }
  for (const Candidate& c : ProximityCandidates(current, &result)) {
    if (c.node != result.lcd_hypothesis) candidates.push_back(c);
  }
  std::vector<Link> added;
  for (const Candidate& candidate : candidates) {
    if (std::optional<Link> link = RegisterCandidate(current, candidate, &result)) {
      map_.AddLink(*link);
      added.push_back(*link);
    }
  }
  OptimizeIfLinked(added, &result);
  ReduceOldestShortTerm(static_cast<size_t>(options_.mapping.short_term_memory), &result);
  result.timings.total_ms = total.ElapsedMs();
  return result;
}

void Mapper::AddNode(const RgbdFrame& frame, FrameFeatures features, MappingFrameResult* result) {
  MapNode node;
  node.id = map_.NextNodeId();
  node.session = *session_;
  node.frame_index = frame.frame_index;
  node.timestamp_s = frame.timestamp_s;
  node.odom_from_body = frame.odom_from_body;
  node.body_from_camera = frame.body_from_camera;
  node.camera = frame.camera;
  node.truth_from_camera = frame.world_from_camera;
  if (previous_node_ == 0) {
    node.map_from_body = frame.odom_from_body;  // a new session starts in its odometry frame
  } else {
    const MapNode& previous = map_.node(previous_node_);
    node.map_from_body =
        previous.map_from_body * previous.odom_from_body.Inverse() * frame.odom_from_body;
  }
  result->node = node.id;
  result->session = node.session;
  result->num_features = static_cast<int>(features.size());

  Stopwatch lcd_watch;
  const LcdResult lcd = lcd_->AddAndDetect(node.id, node.session, features);
  result->timings.lcd_ms = lcd_watch.ElapsedMs();
  result->lcd_status = lcd.status;
  result->lcd_hypothesis = lcd.accepted() ? lcd.hypothesis : 0;

  node.features = CompactFeatures::Encode(features, options_.mapping.descriptor_storage);
  current_features_ = std::move(features);  // the new node's features as extracted
  const NodeId id = node.id;
  map_.AddNode(std::move(node));
  if (previous_node_ != 0) {
    Link odometry;
    odometry.from = previous_node_;
    odometry.to = id;
    odometry.type = LinkType::kOdometry;
    odometry.from_from_to = map_.node(previous_node_).odom_from_body.Inverse() *
                            map_.node(id).odom_from_body;
    odometry.information = OdometryInformation(options_.odometry);
    map_.AddLink(odometry);
    lcd_->graph().AddLink(previous_node_, id, LinkType::kOdometry);
  }
  previous_node_ = id;
  short_term_.push_back(id);
}

std::vector<Mapper::Candidate> Mapper::ProximityCandidates(NodeId current,
                                                           MappingFrameResult* result) {
  std::vector<Candidate> candidates;
  if (!options_.mapping.proximity || options_.mapping.proximity_max_paths == 0) return candidates;
  Stopwatch watch;
  std::set<SessionId> connected;
  for (const auto& group : map_.ConnectedSessionGroups()) {
    if (std::find(group.begin(), group.end(), *session_) != group.end()) {
      connected.insert(group.begin(), group.end());
    }
  }
  std::vector<ProximityNode> nodes;
  for (const auto& [id, node] : map_.nodes()) {
    if (id == current || !lcd_->IsCandidate(id) || !connected.count(node.session)) continue;
    nodes.push_back({id, node.map_from_camera()});
  }
  const Likelihood& likelihood = lcd_->last_likelihood();
  const ProximityResult proximity = FindProximityCandidates(
      options_.MappingProximity(), map_.node(current).map_from_camera(), nodes, lcd_->graph(),
      [&likelihood](NodeId id) { return likelihood.Adjusted(id); },
      [this, current](NodeId id) { return map_.HasLink(current, id); });
  for (const ProximityCandidate& c : proximity.candidates) {
    candidates.push_back({c.node, LinkType::kProximity});
  }
  result->timings.proximity_ms += watch.ElapsedMs();
  return candidates;
}

std::optional<Link> Mapper::RegisterCandidate(NodeId current, const Candidate& candidate,
                                              MappingFrameResult* result) {
  if (map_.HasLink(current, candidate.node)) return std::nullopt;
  const MapNode& old_node = map_.node(candidate.node);
  const MapNode& new_node = map_.node(current);
  Stopwatch watch;
  RegistrationResult registration =
      EstimateTransform(registration_, old_node.features.Decode(), old_node.camera,
                        current_features_, new_node.camera, matcher_.get());
  if (candidate.type == LinkType::kProximity) {
    RejectLongerThan(options_.proximity.path_filtering_radius_m, &registration);
  }
  result->timings.registration_ms += watch.ElapsedMs();
  ++result->registrations;
  if (!registration.accepted()) return std::nullopt;
  Link link;  // from the new node to the old one, as the reference's loop links
  link.from = current;
  link.to = candidate.node;
  link.type = candidate.type;
  const Rigid3d old_body_from_new_body = old_node.body_from_camera *
                                         registration.node_from_query *
                                         new_node.body_from_camera.Inverse();
  link.from_from_to = old_body_from_new_body.Inverse();
  link.information = registration.information;
  return link;
}

void Mapper::OptimizeIfLinked(const std::vector<Link>& added, MappingFrameResult* result) {
  if (added.empty()) return;
  Stopwatch watch;
  const OptimizationSummary summary = OptimizeMap(options_.optimizer, added, &map_);
  result->optimized = true;
  result->optimization_status = summary.status;
  result->links_rejected = static_cast<int>(summary.removed_links.size());
  for (const Link& link : added) {
    if (!map_.HasLink(link.from, link.to)) continue;
    lcd_->graph().AddLink(link.from, link.to, link.type);
    if (link.type == LinkType::kLoopClosure) {
      ++result->loop_closures_added;
    } else {
      ++result->proximity_links_added;
    }
  }
  result->timings.optimization_ms = watch.ElapsedMs();
}

void Mapper::ReduceOldestShortTerm(size_t keep, MappingFrameResult* result) {
  Stopwatch watch;
  while (short_term_.size() > keep) {
    const NodeId oldest = short_term_.front();
    short_term_.pop_front();
    if (!options_.mapping.reduce_graph || !map_.HasNode(oldest)) continue;
    const ReductionResult reduction = ReduceNode(oldest, &map_);
    if (!reduction.reduced) continue;
    lcd_->RemoveNode(oldest);
    for (const Link& merged : reduction.merged_links) {
      lcd_->graph().AddLink(merged.from, merged.to, LinkType::kMerged);
    }
    ++result->nodes_reduced;
  }
  result->timings.reduction_ms += watch.ElapsedMs();
}

void Mapper::SnapshotWords() {
  // The vocabulary as it ends the mapping: words, each node's counts and n_j,
  // and the next word id; the localizer imports it (map_vocabulary.h).
  SetMapVocabulary(lcd_->vocabulary().Export(), &map_);
}

Map Mapper::Finish() {
  MappingFrameResult ignored;
  ReduceOldestShortTerm(0, &ignored);
  SnapshotWords();
  return std::move(map_);
}

}  // namespace duskmap
