// JSON codecs of the session drivers' summaries (slam/core/json_codec.h):
// the timings
//   {"features": {"median_ms": .., "mean_ms": .., "max_ms": ..}, "loop_closure_detection": ..}
// and a map's summary, as `duskmap map` writes it
//   {"sessions": 2, "nodes_per_session": [40, 38], "links_by_type": {"odometry": 76, ...},
//    "connected_session_groups": [[0, 1]], "vocabulary_words": 31000, "memory_bytes": {...}}
#pragma once

#include "slam/core/json_codec.h"
#include "slam/engine/session_runs.h"
#include "slam/map/map_memory_json.h"

namespace duskmap {

template <>
struct JsonCodec<StageTimingSummary> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    f("median_ms", o.median_ms);
    f("mean_ms", o.mean_ms);
    f("max_ms", o.max_ms);
  }
};

template <>
struct JsonCodec<SessionStageTimings> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    f("features", o.features);
    f("loop_closure_detection", o.loop_closure_detection);
    f("proximity_detection", o.proximity_detection);
    f("transformation_estimation", o.transformation_estimation);
    f("optimisation", o.optimisation);
    f("lcd_plus_te", o.lcd_plus_te);
    f("total", o.total);
  }
};

template <>
struct JsonCodec<MapSummary> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    f("sessions", o.num_sessions);
    f("nodes_per_session", o.nodes_per_session);
    f("links_by_type", o.links_by_type);
    f("connected_session_groups", o.connected_groups);
    f("vocabulary_words", o.vocabulary_words);
    f("memory_bytes", o.memory);
  }
};

}  // namespace duskmap
