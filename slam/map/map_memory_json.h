// JSON codec of MapMemory (slam/core/json_codec.h): bytes per component, as
// job summaries and the CLI's map and localize summaries write them.
#pragma once

#include "slam/core/json_codec.h"
#include "slam/map/map_memory.h"

namespace duskmap {

template <>
struct JsonCodec<MapMemory> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    f("descriptors", o.descriptors_bytes);
    f("keypoints_points", o.keypoints_points_bytes);
    f("words_index", o.words_index_bytes);
    f("graph", o.graph_bytes);
    f("filter", o.filter_bytes);
  }
};

}  // namespace duskmap
