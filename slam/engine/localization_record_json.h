// JSON codecs of the parts of a localization record that are one field per
// key (slam/core/json_codec.h): its outcome's name (the one spelling, which
// LocalizationOutcomeName returns too), its stage timings and each transform
// estimation it tried. The record itself is written by
// LocalizationRecordToJson (record_io.h), which adds the keys a field list
// cannot say (values null unless the frame re-localized, the pose, the check).
//   timings:  {"features": 9.1, "lcd": 3.2, "proximity": 0.1, "registration": 4.0, "total": 16.5}
//   attempt:  {"node": 5, "session": 0, "source": "proximity", "status": "too_few_inliers",
//              "matches": 30, "inliers": 12, "search_distance_m": 0.4, "estimate_distance_m": null,
//              "truth_distance_m": null, "truth_angle_deg": null}
#pragma once

#include <utility>

#include "slam/core/graph_types_json.h"
#include "slam/core/json_codec.h"
#include "slam/engine/localization_record.h"
#include "slam/engine/odometry_cache_json.h"
#include "slam/registration/transform_estimation_json.h"
#include "slam/retrieval/lcd_result_json.h"

namespace duskmap {

template <>
struct JsonEnumNames<LocalizationOutcome> {
  static constexpr std::pair<LocalizationOutcome, const char*> kNames[] = {
      {LocalizationOutcome::kRelocalized, "relocalized"},
      {LocalizationOutcome::kBadSignature, "bad_signature"},
      {LocalizationOutcome::kNoCandidate, "no_candidate"},
      {LocalizationOutcome::kRegistrationRejected, "registration_rejected"},
      {LocalizationOutcome::kOdometryCacheWaiting, "odometry_cache_waiting"},
      {LocalizationOutcome::kOdometryCacheRejected, "odometry_cache_rejected"}};
};

template <>
struct JsonCodec<LocalizationTimings> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    f("features", o.features_ms);
    f("lcd", o.lcd_ms);
    f("proximity", o.proximity_ms);
    f("registration", o.registration_ms);
    f("total", o.total_ms);
  }
};

template <>
struct JsonCodec<CandidateAttempt> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    f("node", o.node);
    f("session", o.session);
    f("source", o.source);
    f("status", o.status);
    f("matches", o.matches);
    f("inliers", o.inliers);
    f("search_distance_m", o.search_distance_m);      // null for the LCD hypothesis
    f("estimate_distance_m", o.estimate_distance_m);  // null without a transform
    f("truth_distance_m", o.truth_distance_m);  // null when unknown
    f("truth_angle_deg", o.truth_angle_deg);
  }
};

}  // namespace duskmap
