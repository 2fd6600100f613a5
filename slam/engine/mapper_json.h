// JSON codec of a mapping frame's stage timings (slam/core/json_codec.h), as
// the per-frame mapping records write them (MappingResultToJson, record_io.h):
//   {"features": 9.1, "lcd": 3.2, "proximity": 0.1, "registration": 4.0,
//    "optimization": 12.0, "reduction": 0.0, "total": 28.4}
#pragma once

#include "slam/core/json_codec.h"
#include "slam/engine/mapper.h"

namespace duskmap {

template <>
struct JsonCodec<MappingTimings> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    f("features", o.features_ms);
    f("lcd", o.lcd_ms);
    f("proximity", o.proximity_ms);
    f("registration", o.registration_ms);
    f("optimization", o.optimization_ms);
    f("reduction", o.reduction_ms);
    f("total", o.total_ms);
  }
};

}  // namespace duskmap
