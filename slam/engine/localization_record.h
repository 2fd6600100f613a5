// The typed per-frame record of the localization-only phase: what happened,
// why a frame did not re-localize, the corrected pose and the stage timings.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "slam/core/graph_types.h"
#include "slam/core/rigid3.h"
#include "slam/engine/odometry_cache.h"
#include "slam/eval/relocalization_metrics.h"
#include "slam/registration/transform_estimation.h"
#include "slam/retrieval/lcd_result.h"

namespace duskmap {

enum class LocalizationOutcome {
  kRelocalized,           // a candidate's transform was accepted
  kBadSignature,          // too few features to detect loops, and no proximity candidate
  kNoCandidate,           // LCD proposed no hypothesis and proximity found none
  kRegistrationRejected,  // every candidate's transform was rejected (see registration_status)
  // Odometry-cache validation on (spec §9.2): an accepted transform was kept
  // in the cache but not applied, as the cache held no earlier localization.
  kOdometryCacheWaiting,
  // Odometry-cache validation on: every accepted transform was inconsistent
  // with the cached odometry and localizations.
  kOdometryCacheRejected,
};

const char* LocalizationOutcomeName(LocalizationOutcome outcome);

struct LocalizationTimings {
  double features_ms = 0.0;      // extraction (0 when features were given)
  double lcd_ms = 0.0;           // quantization, likelihood, Bayes filter
  double proximity_ms = 0.0;     // candidate search around the corrected pose
  double registration_ms = 0.0;  // transform estimations (TE)
  double total_ms = 0.0;
};

// One transform estimation tried this frame (in the order tried).
struct CandidateAttempt {
  NodeId node = 0;
  SessionId session = -1;
  LinkType source = LinkType::kLoopClosure;  // LCD hypothesis or proximity
  RegistrationStatus status = RegistrationStatus::kNoFeatures;
  int matches = 0;  // first-pass correspondences with a map 3D point
  int inliers = 0;
  // Proximity candidates: the node's distance to the pose estimate the
  // search ran from (m); nullopt for the LCD hypothesis.
  std::optional<double> search_distance_m;
  // The estimated node-to-frame translation |t| (m); nullopt unless the
  // registration produced a transform.
  std::optional<double> estimate_distance_m;
  // Ground-truth distance between the node's camera and the frame's camera
  // (m, deg); nullopt unless both have ground truth (filled by the localizer
  // from the frame's world_from_camera and the node's truth_from_camera: it
  // says whether the candidate was the right place, not whether TE was right).
  std::optional<double> truth_distance_m;
  std::optional<double> truth_angle_deg;
};

struct LocalizationRecord {
  int64_t frame_index = 0;
  double timestamp_s = 0.0;
  bool relocalized = false;
  LocalizationOutcome outcome = LocalizationOutcome::kNoCandidate;
  LcdStatus lcd_status = LcdStatus::kNoCandidates;
  NodeId lcd_hypothesis = 0;  // 0 when LCD accepted none
  double lcd_score = 0.0;     // 1 - P(new place)
  std::vector<LcdHypothesis> lcd_top;  // best places by posterior (LcdOptions' count)
  int proximity_candidates = 0;
  int candidates_tried = 0;
  std::vector<CandidateAttempt> attempts;  // every transform estimation of the frame
  // Status of the last transform estimation tried (the accepted one when
  // re-localized); nullopt when none ran.
  std::optional<RegistrationStatus> registration_status;
  NodeId matched_node = 0;         // 0 unless re-localized
  SessionId matched_session = -1;  // session of matched_node
  // The accepted link's type, as the reference types it (spec §5.4): loop
  // closure for the LCD hypothesis, also when proximity proposed it first;
  // proximity for any other proximity target.
  LinkType matched_by = LinkType::kLoopClosure;
  int inliers = 0;                 // of the accepted (or last tried) transform
  // Odometry-cache validation of the last accepted transform (nullopt when
  // the validation is off or no transform was accepted), with the largest
  // normalised link error of the validated cache graph.
  std::optional<CacheValidation> cache_validation;
  double cache_max_error_ratio = 0.0;
  int num_features = 0;
  // Change of the corrected camera position at this re-localization, mm;
  // nullopt at the first one (no prior pose) and when not re-localized.
  std::optional<double> jump_mm;
  // Corrected camera pose (map_from_odom * odom_from_camera); nullopt until
  // the first re-localization.
  std::optional<Rigid3d> map_from_camera;
  double distance_since_last_m = 0.0;  // odometry path length since the last re-localization
  LocalizationTimings timings;
  // Filled by EvaluateLocalization when the frame has ground truth.
  std::optional<RelocalizationCheck> check;
};

}  // namespace duskmap
