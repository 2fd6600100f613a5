#include "slam/engine/localizer.h"

#include <algorithm>
#include <cmath>
#include <set>

#include "slam/core/check.h"
#include "slam/core/timer.h"
#include "slam/engine/localization_record_json.h"
#include "slam/features/feature_factory.h"
#include "slam/map/map_vocabulary.h"
#include "slam/retrieval/proximity.h"

namespace duskmap {

const char* LocalizationOutcomeName(LocalizationOutcome outcome) { return JsonEnumName(outcome); }

namespace {

// The diagnostic record of one transform estimation, with the ground-truth
// distance between the node's camera and the frame's when both have it.
CandidateAttempt AttemptOf(NodeId id, LinkType source, const MapNode& node, const RgbdFrame& frame,
                           const RegistrationResult& registration) {
  CandidateAttempt attempt;
  attempt.node = id;
  attempt.session = node.session;
  attempt.source = source;
  attempt.status = registration.status;
  attempt.matches = registration.matches_first_pass;
  attempt.inliers = registration.num_inliers;
  if (registration.accepted() || registration.status == RegistrationStatus::kTranslationTooLong) {
    attempt.estimate_distance_m = registration.node_from_query.translation.norm();
  }
  if (node.truth_from_camera && frame.world_from_camera) {
    const Rigid3d node_from_frame = node.truth_from_camera->Inverse() * *frame.world_from_camera;
    attempt.truth_distance_m = node_from_frame.translation.norm();
    attempt.truth_angle_deg =
        RotationAngleRad(node_from_frame.rotation, Eigen::Quaterniond::Identity()) * 180.0 / M_PI;
  }
  return attempt;
}

}  // namespace

Localizer::Localizer(const Map& map, const EngineOptions& options, const MapWords* words)
    : map_(map), options_(options), registration_(options.Registration()) {
  options_.Check();
  SLAM_THROW_IF_NOT(ConfigError, map.metadata().feature_type == options_.features.type)
      << "Localizer: the map was built with feature type '" << map.metadata().feature_type
      << "', the options ask for '" << options_.features.type << "'";
  // The extractor is made on the first frame that needs it: frames with
  // their features (a feature cache) never do, and some extractors take a
  // while to build (BRISK's sampling pattern).
  matcher_ = CreateFeatureMatcher(options_.matcher);
  lcd_ = std::make_unique<LoopClosureDetector>(options_.LoopClosure());
  // The mapper's vocabulary, restored exactly from the map (as the reference
  // loads it from its database); every node is a candidate place.
  lcd_->ImportMap(MapVocabularySnapshot(map_, words != nullptr ? *words : map_.words()),
                  [this](NodeId id) { return map_.node(id).session; });
  for (const auto& [key, link] : map_.links()) lcd_->graph().AddLink(link.from, link.to, link.type);
  if (options_.localization.odometry_cache_size > 0) {
    OdometryCacheOptions cache;
    cache.size = options_.localization.odometry_cache_size;
    cache.max_error_ratio = options_.localization.odometry_cache_max_error_ratio;
    cache.odometry_linear_sigma_m = options_.odometry.linear_sigma_m;
    cache.odometry_angular_sigma_rad = options_.odometry.angular_sigma_rad;
    cache.max_iterations = options_.optimizer.max_iterations;
    cache_ = std::make_unique<OdometryCache>(cache);
  }
}

Localizer::~Localizer() = default;

LocalizationRecord Localizer::ProcessFrame(const RgbdFrame& frame) {
  if (extractor_ == nullptr) extractor_ = CreateFeatureExtractor(options_.features);
  Stopwatch watch;
  const FrameFeatures features = extractor_->ExtractFrame(frame);
  const double features_ms = watch.ElapsedMs();
  LocalizationRecord record = ProcessFrame(frame, features);
  record.timings.features_ms = features_ms;
  record.timings.total_ms += features_ms;
  return record;
}

LocalizationRecord Localizer::ProcessFrame(const RgbdFrame& frame,
                                           const FrameFeatures& features) {
  Stopwatch total;
  LocalizationRecord record;
  record.frame_index = frame.frame_index;
  record.timestamp_s = frame.timestamp_s;
  record.num_features = static_cast<int>(features.size());
  const Rigid3d odom_from_camera = frame.odom_from_camera();
  if (cache_) cache_->AddFrame(odom_from_camera);

  Stopwatch lcd_watch;
  const LcdResult lcd = lcd_->Localize(features);
  record.timings.lcd_ms = lcd_watch.ElapsedMs();
  record.lcd_status = lcd.status;
  record.lcd_hypothesis = lcd.accepted() ? lcd.hypothesis : 0;
  record.lcd_score = lcd.score;
  record.lcd_top = lcd.top;

  std::vector<Candidate> candidates = ProximityCandidates(odom_from_camera, &record);
  for (Candidate& c : candidates) c.is_hypothesis = lcd.accepted() && c.node == lcd.hypothesis;
  if (lcd.accepted()) candidates.push_back({lcd.hypothesis, LinkType::kLoopClosure, {}, true});
  const bool had_pose = map_from_odom_.has_value();
  const Eigen::Vector3d previous_position =
      had_pose ? Eigen::Vector3d((*map_from_odom_ * odom_from_camera).translation)
               : Eigen::Vector3d::Zero();
  bool waiting = false, cache_rejected = false;
  std::set<NodeId> tried;
  for (const Candidate& candidate : candidates) {
    // The proximity target may be the hypothesis itself: register it once.
    if (!tried.insert(candidate.node).second) continue;
    const Attempt attempt = TryCandidate(candidate, frame, features, &record);
    if (attempt == Attempt::kApplied) break;
    if (attempt == Attempt::kWaiting) {
      waiting = true;
      break;
    }
    cache_rejected |= record.cache_validation == CacheValidation::kRejected;
  }
  if (record.relocalized) {
    record.outcome = LocalizationOutcome::kRelocalized;
    if (had_pose) {
      record.jump_mm =
          1000.0 * ((*map_from_odom_ * odom_from_camera).translation - previous_position).norm();
    }
  } else if (waiting) {
    record.outcome = LocalizationOutcome::kOdometryCacheWaiting;
  } else if (cache_rejected) {
    record.outcome = LocalizationOutcome::kOdometryCacheRejected;
  } else if (record.candidates_tried > 0) {
    record.outcome = LocalizationOutcome::kRegistrationRejected;
  } else {
    record.outcome = lcd.status == LcdStatus::kBadSignature ? LocalizationOutcome::kBadSignature
                                                            : LocalizationOutcome::kNoCandidate;
  }
  if (map_from_odom_) record.map_from_camera = *map_from_odom_ * odom_from_camera;
  UpdateDistance(frame, &record);
  record.timings.total_ms = total.ElapsedMs();
  return record;
}

std::vector<Localizer::Candidate> Localizer::ProximityCandidates(const Rigid3d& odom_from_camera,
                                                                 LocalizationRecord* record) {
  std::vector<Candidate> candidates;
  const LocalizationOptions& o = options_.localization;
  if (!o.proximity || o.proximity_max_paths == 0 ||
      (!map_from_odom_ && !o.proximity_before_relocalized)) {
    return candidates;
  }
  Stopwatch watch;
  std::vector<ProximityNode> nodes;
  if (map_from_odom_) {
    // Poses are comparable only within the group of sessions the last
    // re-localization belongs to (unconnected groups have their own frames).
    std::set<SessionId> group;
    for (const auto& g : map_.ConnectedSessionGroups()) {
      if (std::find(g.begin(), g.end(), localized_session_) != g.end()) group.insert(g.begin(), g.end());
    }
    for (const auto& [id, node] : map_.nodes()) {
      if (group.count(node.session)) nodes.push_back({id, node.map_from_camera()});
    }
  } else {
    // Not yet re-localized: the odometry pose taken as a map pose (the
    // reference's map correction starts as identity with -loc_null), every
    // node a candidate.
    for (const auto& [id, node] : map_.nodes()) nodes.push_back({id, node.map_from_camera()});
  }
  const Rigid3d map_from_camera =
      map_from_odom_ ? *map_from_odom_ * odom_from_camera : odom_from_camera;
  const Likelihood& likelihood = lcd_->last_likelihood();
  const ProximityResult proximity = FindProximityCandidates(
      options_.LocalizationProximity(), map_from_camera, nodes, lcd_->graph(),
      [&likelihood](NodeId id) { return likelihood.Adjusted(id); });
  for (const ProximityCandidate& c : proximity.candidates) {
    candidates.push_back({c.node, LinkType::kProximity, c.distance_m});
  }
  record->proximity_candidates = static_cast<int>(candidates.size());
  record->timings.proximity_ms = watch.ElapsedMs();
  return candidates;
}

Localizer::Attempt Localizer::TryCandidate(const Candidate& candidate, const RgbdFrame& frame,
                                           const FrameFeatures& features,
                                           LocalizationRecord* record) {
  const MapNode& node = map_.node(candidate.node);
  Stopwatch watch;
  // The node's rows shared with words are read from the vocabulary.
  RegistrationResult registration =
      EstimateTransform(registration_, node.features.Decode(&lcd_->vocabulary()), node.camera,
                        features, frame.camera, matcher_.get());
  if (candidate.type == LinkType::kProximity && !candidate.is_hypothesis) {
    RejectLongerThan(options_.proximity.path_filtering_radius_m, &registration);
  }
  record->timings.registration_ms += watch.ElapsedMs();
  ++record->candidates_tried;
  record->registration_status = registration.status;
  record->inliers = registration.num_inliers;
  record->attempts.push_back(AttemptOf(candidate.node, candidate.type, node, frame, registration));
  record->attempts.back().search_distance_m = candidate.search_distance_m;
  if (!registration.accepted()) return Attempt::kRejected;
  if (cache_) {
    const CacheValidationResult validation =
        cache_->Validate(candidate.node, node.map_from_camera(), registration.node_from_query,
                         registration.information);
    record->cache_validation = validation.status;
    record->cache_max_error_ratio =
        std::max(validation.max_linear_ratio, validation.max_angular_ratio);
    if (validation.status == CacheValidation::kRejected) return Attempt::kRejected;
    if (validation.status == CacheValidation::kWaiting) return Attempt::kWaiting;
  }
  const Rigid3d map_from_camera = node.map_from_camera() * registration.node_from_query;
  map_from_odom_ = map_from_camera * frame.odom_from_camera().Inverse();
  localized_session_ = node.session;
  record->relocalized = true;
  record->matched_node = candidate.node;
  record->matched_session = node.session;
  record->matched_by = candidate.is_hypothesis ? LinkType::kLoopClosure : candidate.type;
  return Attempt::kApplied;
}

void Localizer::UpdateDistance(const RgbdFrame& frame, LocalizationRecord* record) {
  const Eigen::Vector3d position = frame.odom_from_camera().translation;
  if (last_odom_position_) distance_since_last_m_ += (position - *last_odom_position_).norm();
  last_odom_position_ = position;
  record->distance_since_last_m = distance_since_last_m_;
  if (record->relocalized) distance_since_last_m_ = 0.0;
}

}  // namespace duskmap
