// JSON codecs of loop-closure and proximity detection's options
// (slam/core/json_codec.h). Keys are the option fields:
//   {"vocabulary": {"nndr_ratio": 0.8, "max_features_per_node": 400,
//                   "index": {"binary_kind": "bit_kdtree", "checks": 32}},
//    "bayes": {"virtual_place_prior": 0.9}, "loop_threshold": 0.11}
#pragma once

#include "slam/core/json_codec.h"
#include "slam/retrieval/loop_closure_detector.h"
#include "slam/retrieval/proximity.h"
#include "slam/vocabulary/vocabulary_options_json.h"

namespace duskmap {

template <>
struct JsonCodec<BayesFilterOptions> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    f("prediction", o.prediction);
    f("virtual_place_prior", o.virtual_place_prior);
  }
};

template <>
struct JsonCodec<LoopClosureOptions> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    f("vocabulary", o.vocabulary);
    f("bayes", o.bayes);
    f("loop_threshold", o.loop_threshold);
    f("aggressive_loop_threshold", o.aggressive_loop_threshold);
    f("loop_ratio", o.loop_ratio);
    f("short_term_memory_size", o.short_term_memory_size);
    f("top_hypotheses", o.top_hypotheses);
  }
};

template <>
struct JsonCodec<ProximityOptions> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    f("local_radius_m", o.local_radius_m);
    f("max_angle_deg", o.max_angle_deg);
    f("max_paths", o.max_paths);
    f("path_filtering_radius_m", o.path_filtering_radius_m);
    f("max_path_depth", o.max_path_depth);
    f("forward_axis", o.forward_axis);
  }
};

}  // namespace duskmap
