// JSON codec of EngineOptions (slam/core/json_codec.h), composed from the
// modules' codecs: every key of every sub-struct can be set from an engine
// config, except those the engine fills in itself (JsonDerivedKeys: the seed,
// the binary distance, the vocabulary's features per node, the short-term
// memory and the proximity paths), which a config sets at the engine level.
#pragma once

#include "slam/core/json_codec.h"
#include "slam/engine/engine_options.h"
#include "slam/features/feature_options_json.h"
#include "slam/graph/pose_graph_options_json.h"
#include "slam/registration/registration_options_json.h"
#include "slam/retrieval/lcd_options_json.h"

namespace duskmap {

template <>
struct JsonCodec<OdometryNoiseOptions> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    f("linear_sigma_m", o.linear_sigma_m);
    f("angular_sigma_rad", o.angular_sigma_rad);
  }
};

template <>
struct JsonCodec<MappingOptions> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    f("proximity", o.proximity);
    f("proximity_max_paths", o.proximity_max_paths);
    f("reduce_graph", o.reduce_graph);
    f("short_term_memory", o.short_term_memory);
    f("descriptor_storage", o.descriptor_storage);
  }
};

template <>
struct JsonCodec<LocalizationOptions> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    f("proximity", o.proximity);
    f("proximity_max_paths", o.proximity_max_paths);
    f("odometry_cache_size", o.odometry_cache_size);
    f("odometry_cache_max_error_ratio", o.odometry_cache_max_error_ratio);
    f("proximity_before_relocalized", o.proximity_before_relocalized);
  }
};

template <>
struct JsonCodec<EngineOptions> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    f("features", o.features);
    f("loop_closure", o.loop_closure,
      {{"vocabulary.max_features_per_node", "features.vocabulary_features"},
       {"vocabulary.index.binary_distance", "binary_distance"},
       {"short_term_memory_size", "mapping.short_term_memory"}});
    f("proximity", o.proximity,
      {{"max_paths", "mapping.proximity_max_paths or localization.proximity_max_paths"}});
    f("registration", o.registration,
      {{"matching.random_seed", "random_seed"},
       {"matching.binary_distance", "binary_distance"},
       {"pnp.random_seed", "random_seed"}});
    f("matcher", o.matcher);
    f("optimizer", o.optimizer);
    f("odometry", o.odometry);
    f("mapping", o.mapping);
    f("localization", o.localization);
    f("random_seed", o.random_seed);
    f("binary_distance", o.binary_distance);
  }
};

}  // namespace duskmap
