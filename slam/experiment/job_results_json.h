// JSON codecs of the job summaries (slam/core/json_codec.h): the one field
// list per struct that writes a job's summary.json and reads it back for the
// report. Keys are those of the summaries already on disk. A summary's keys
// come in two groups: those every summary has held (VisitRequired: a summary
// without one is malformed) and those added later (VisitAddedLater: absent
// from older summaries, which read them as the defaults). A codec without
// VisitRequired (StageTimesMs) requires every key.
//   {"num_frames": 90, "num_within_threshold": [61, 70, 74],
//    "mean_times_ms": {"features": 9.1, ...}, "map_load_s": 0.04, ...}
#pragma once

#include "slam/core/json_codec.h"
#include "slam/experiment/job_results.h"

namespace duskmap {

template <>
struct JsonCodec<StageTimesMs> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {  // every key required
    f("features", o.features);
    f("loop_closure_detection", o.loop_closure_detection);
    f("proximity_detection", o.proximity_detection);
    f("transformation_estimation", o.transformation_estimation);
    f("optimisation", o.optimisation);
    f("total", o.total);
  }
};

template <>
struct JsonCodec<LocalizationJobSummary> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    VisitRequired(f, o);
    VisitAddedLater(f, o);
  }
  template <typename F, typename O>
  static void VisitRequired(F& f, O& o) {
    f("num_frames", o.num_frames);
    f("num_relocalized", o.num_relocalized);
    f("num_no_candidate", o.num_no_candidate);
    f("has_ground_truth", o.has_ground_truth);
    f("num_within_threshold", o.num_within_threshold);
    f("num_wrong", o.num_wrong);
    f("mean_inliers_pct", o.mean_inliers_pct);
    f("mean_jump_mm", o.mean_jump_mm);
    f("mean_features", o.mean_features);
    f("max_gap_m", o.max_gap_m);
    f("num_within_55cm", o.num_within_55cm);
    f("matched_session_per_frame", o.matched_session_per_frame);
    f("mean_times_ms", o.mean_times_ms);
    f("median_lcd_te_ms", o.median_lcd_te_ms);
    f("memory_bytes", o.memory_bytes);
  }
  template <typename F, typename O>
  static void VisitAddedLater(F& f, O& o) {
    f("map_load_s", o.map_load_s);
    f("map_from_cache", o.map_from_cache);
    f("localizer_setup_s", o.localizer_setup_s);
    f("index_restore_s", o.index_restore_s);
    f("index_restored", o.index_restored);
    f("index_rebuild_reason", o.index_rebuild_reason);
    f("num_within_55cm_bound", o.num_within_55cm_bound);
  }
};

template <>
struct JsonCodec<ExtractionTimesMs> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {  // every key required
    f("median", o.median);
    f("mean", o.mean);
    f("max", o.max);
  }
};

//   {"extractor": "sift", "session": "1", "frames": 90, "mean_features": 998.2,
//    "extraction_ms": {"median": 41.0, "mean": 42.3, "max": 60.1},
//    "shared_cache": "stored 0123456789abcdef"}
template <>
struct JsonCodec<ExtractJobSummary> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    VisitRequired(f, o);
    f("shared_cache", o.shared_cache, JsonOmitEmpty{});  // only with a cache kept across runs
  }
  template <typename F, typename O>
  static void VisitRequired(F& f, O& o) {
    f("extractor", o.extractor);
    f("session", o.session);
    f("frames", o.frames);
    f("mean_features", o.mean_features);
    f("extraction_ms", o.extraction_ms);
  }
};

template <>
struct JsonCodec<MapJobSummary> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    VisitRequired(f, o);
    VisitAddedLater(f, o);
  }
  template <typename F, typename O>
  static void VisitRequired(F& f, O& o) {
    f("num_nodes", o.num_nodes);
    f("nodes_per_session", o.nodes_per_session);
    f("links_per_type", o.links_per_type);
    f("num_connected_components", o.num_connected_components);
    f("vocabulary_words", o.vocabulary_words);
    f("descriptor_bytes_per_feature", o.descriptor_bytes_per_feature);
    f("memory_bytes", o.memory_bytes);
    f("ate_mm", o.ate_mm);
    f("mean_features", o.mean_features);
    f("mean_times_ms", o.mean_times_ms);
    f("build_wall_s", o.build_wall_s);
  }
  template <typename F, typename O>
  static void VisitAddedLater(F& f, O& o) {
    f("index_build_s", o.index_build_s);
  }
};

}  // namespace duskmap
