// Options of the SLAM engine (both phases), composed from the sub-modules'
// options (STYLE.md recommendation 3): the accessors copy the engine-wide
// values (seed, features per node) into each sub-struct, so no module reads a
// global. Defaults follow the paper's runs (spec appendix A).
#pragma once

#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

#include "slam/core/json_fields.h"
#include "slam/features/feature_options.h"
#include "slam/features/matcher_options.h"
#include "slam/graph/pose_graph_optimizer.h"
#include "slam/map/compact_features.h"
#include "slam/map/map_store.h"
#include "slam/registration/transform_estimation.h"
#include "slam/retrieval/loop_closure_detector.h"
#include "slam/retrieval/proximity.h"

namespace duskmap {

struct OdometryNoiseOptions {
  // Odometry link information = diag(1/sigma^2); frames carry no covariance.
  double linear_sigma_m = 0.01;    // per odometry link, metres
  double angular_sigma_rad = 0.01; // per odometry link, radians
  void Check() const;
};

struct MappingOptions {
  bool proximity = true;         // RGBD/ProximityBySpace
  int proximity_max_paths = 3;   // RGBD/ProximityMaxPaths while mapping
  bool reduce_graph = false;     // Mem/ReduceGraph (spec §8), "1-2-3-4-5-6" maps
  int short_term_memory = 10;    // Mem/STMSize: nodes are reduced when they leave it
  // How map nodes keep float descriptors (slam/map/compact_features.h):
  // 8-bit quantized (default, a quarter of the bytes) or as extracted.
  DescriptorStorage descriptor_storage = DescriptorStorage::kUint8;
  void Check() const;
};

struct LocalizationOptions {
  bool proximity = true;         // RGBD/ProximityBySpace (only once re-localized)
  int proximity_max_paths = 1;   // RGBD/ProximityMaxPaths of the paper's localization runs
  // Reference odometry-cache validation (spec §9.2, RGBD/MaxOdomCacheSize,
  // slam/engine/odometry_cache.h): frames kept, >= 2; 0 = paper-era rule
  // (correct from the first accepted link, no validation).
  int odometry_cache_size = 0;
  // RGBD/OptimizeMaxError of the cache validation (the mapping optimiser's
  // max_error_ratio is 0 in the paper's runs, so it has its own value).
  double odometry_cache_max_error_ratio = 3.0;
  // Proximity before the first re-localization (the paper's runs, -loc_null:
  // spec §5 and §9.1): the map->odometry correction starts as identity, so the
  // search runs around the odometry pose taken as a map pose, over every node.
  bool proximity_before_relocalized = true;
  void Check() const;
};

struct EngineOptions {
  // The modules' own defaults are the reference's current ones; the engine's
  // are the paper's runs (spec appendix A), which differ in three places:
  // RGBD/OptimizeMaxError 0 (no rejection of optimisations),
  // Kp/BadSignRatio 0.2 and Kp/ByteToFloat true (binary_distance byte_l1).
  // configs/engine_paper.json spells them all out.
  EngineOptions();

  FeatureOptions features;
  LoopClosureOptions loop_closure;
  ProximityOptions proximity;
  RegistrationOptions registration;
  // Registration's descriptor matcher: "nndr" or "superglue" (SuperPoint only;
  // no second, window-guided pass then, as in the paper's SuperGlue runs).
  MatcherOptions matcher;
  PoseGraphOptimizerOptions optimizer;
  OdometryNoiseOptions odometry;
  MappingOptions mapping;
  LocalizationOptions localization;
  uint64_t random_seed = 0;  // seeds registration RANSAC and KD-trees
  // How binary descriptors are compared in the vocabulary and in
  // registration's first-pass matching (binary_distance.h): the L1 of the
  // byte values, as the paper's runs (Kp/ByteToFloat true), or Hamming (the
  // reference's default). The guess-window pass always uses Hamming.
  BinaryDistance binary_distance = BinaryDistance::kByteL1;

  void Check() const;

  // Sub-options with the shared values filled in.
  LoopClosureOptions LoopClosure() const;
  RegistrationOptions Registration() const;
  ProximityOptions MappingProximity() const;
  ProximityOptions LocalizationProximity() const;
  // How a localizer loads its map (LoadMapAndWords): node rows shared with
  // the words, keypoint responses kept only for a matcher that reads them.
  MapLoadOptions LocalizationMapLoad() const;
};

// Reads EngineOptions from JSON such as
//   {"features": {...}, "registration": {"min_inliers": 20, "pnp": {"max_trials": 500}},
//    "loop_closure": {"loop_threshold": 0.11, "vocabulary": {"bad_signature_ratio": 0.2}},
//    "proximity": {"local_radius_m": 1}, "optimizer": {"max_error_ratio": 0},
//    "mapping": {"reduce_graph": true}, "localization": {"odometry_cache_size": 0},
//    "random_seed": 0, "binary_distance": "byte_l1"}
// Every sub-struct's keys are its own codec's (engine_options_json.h); the
// fields the engine fills in itself (seeds, binary distance, features per
// node, short-term memory, proximity paths) are refused where they would be
// ignored, naming the key that sets them, and the keys of older configs are
// refused with their new names. Unknown keys are rejected with their path;
// the result is checked.
EngineOptions ReadEngineOptions(JsonFields& fields);
EngineOptions ReadEngineOptionsFile(const std::string& path);

// Every engine option as JSON, as ReadEngineOptions reads it (stored in the
// map's metadata).
nlohmann::json EngineOptionsToJson(const EngineOptions& options);

}  // namespace duskmap
