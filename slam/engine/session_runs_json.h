// JSON codecs of the session drivers' timing summaries (slam/core/json_codec.h):
//   {"features": {"median_ms": .., "mean_ms": .., "max_ms": ..}, "loop_closure_detection": ..}
#pragma once

#include "slam/core/json_codec.h"
#include "slam/engine/session_runs.h"

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

}  // namespace duskmap
