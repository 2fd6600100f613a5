#include "slam/engine/engine_options.h"

#include <cstring>
#include <utility>

#include "slam/core/check.h"
#include "slam/engine/engine_options_json.h"
#include "slam/features/feature_registry.h"

namespace duskmap {

EngineOptions::EngineOptions() {
  optimizer.max_error_ratio = 0.0;                    // RGBD/OptimizeMaxError (paper: 0)
  loop_closure.vocabulary.bad_signature_ratio = 0.2;  // Kp/BadSignRatio (paper: 0.2)
  // Float words in 8 bits, as the nodes' descriptors (a quarter of the
  // vocabulary's descriptor bytes; docs/engine.md, "Quantized words").
  loop_closure.vocabulary.index.float_storage = DescriptorStorage::kUint8;
}

void OdometryNoiseOptions::Check() const {
  SLAM_THROW_IF_NOT(ConfigError, linear_sigma_m > 0.0)
      << "EngineOptions.odometry.linear_sigma_m: must be > 0, got " << linear_sigma_m;
  SLAM_THROW_IF_NOT(ConfigError, angular_sigma_rad > 0.0)
      << "EngineOptions.odometry.angular_sigma_rad: must be > 0, got " << angular_sigma_rad;
}

void MappingOptions::Check() const {
  SLAM_THROW_IF_NOT(ConfigError, proximity_max_paths >= 0)
      << "EngineOptions.mapping.proximity_max_paths: must be >= 0, got " << proximity_max_paths;
  SLAM_THROW_IF_NOT(ConfigError, short_term_memory >= 1)
      << "EngineOptions.mapping.short_term_memory: must be >= 1, got " << short_term_memory;
}

void LocalizationOptions::Check() const {
  SLAM_THROW_IF_NOT(ConfigError, proximity_max_paths >= 0)
      << "EngineOptions.localization.proximity_max_paths: must be >= 0, got "
      << proximity_max_paths;
  SLAM_THROW_IF_NOT(ConfigError, odometry_cache_size == 0 || odometry_cache_size >= 2)
      << "EngineOptions.localization.odometry_cache_size: must be 0 (paper-era rule) or >= 2, "
         "got "
      << odometry_cache_size;
  SLAM_THROW_IF_NOT(ConfigError, odometry_cache_max_error_ratio > 0.0)
      << "EngineOptions.localization.odometry_cache_max_error_ratio: must be > 0, got "
      << odometry_cache_max_error_ratio;
}

void EngineOptions::Check() const {
  features.Check();
  LoopClosure().Check();
  proximity.Check();
  Registration().Check();
  matcher.Check();
  const FeatureType* matched = FeatureTypeOfMatcher(matcher.type);
  SLAM_THROW_IF_NOT(ConfigError, matched == nullptr || matched->name == features.type)
      << "EngineOptions.matcher.type: " << matcher.type << " needs features.type " << matched->name
      << ", got " << features.type;
  optimizer.Check();
  odometry.Check();
  mapping.Check();
  localization.Check();
}

LoopClosureOptions EngineOptions::LoopClosure() const {
  LoopClosureOptions o = loop_closure;
  // Kp/MaxFeatures is a feature setting in the paper's tables; one value.
  o.vocabulary.max_features_per_node = features.vocabulary_features;
  o.vocabulary.index.binary_distance = binary_distance;
  o.short_term_memory_size = mapping.short_term_memory;
  return o;
}

RegistrationOptions EngineOptions::Registration() const {
  RegistrationOptions o = registration;
  o.pnp.random_seed = random_seed;
  o.matching.random_seed = random_seed;
  o.matching.binary_distance = binary_distance;
  return o;
}

ProximityOptions EngineOptions::MappingProximity() const {
  ProximityOptions o = proximity;
  o.max_paths = mapping.proximity_max_paths;
  return o;
}

ProximityOptions EngineOptions::LocalizationProximity() const {
  ProximityOptions o = proximity;
  o.max_paths = localization.proximity_max_paths;
  return o;
}

MapLoadOptions EngineOptions::LocalizationMapLoad() const {
  MapLoadOptions o;
  o.share_node_rows_with_words = true;
  o.keep_keypoint_responses = matcher.ReadsKeypointResponses();
  return o;
}

namespace {

// Keys of engine configs before the options had one codec each; a config
// that still uses one is told its new name.
constexpr std::pair<const char*, const char*> kRenamedKeys[] = {
    {"registration.float_nndr_ratio", "registration.matching.float_ratio"},
    {"registration.binary_nndr_ratio", "registration.matching.binary_ratio"},
    {"registration.max_reprojection_error_px", "registration.pnp.max_reprojection_error_px"},
    {"loop_closure.bad_signature_ratio", "loop_closure.vocabulary.bad_signature_ratio"},
    {"loop_closure.word_storage", "loop_closure.vocabulary.index.float_storage"}};

void RejectRenamedKeys(const JsonFields& fields) {
  for (const auto& [old_key, new_key] : kRenamedKeys) {
    SLAM_THROW_IF_NOT(ConfigError,
                      json_codec_internal::FindPath(fields.object(), old_key) == nullptr)
        << fields.where() << "." << old_key << ": renamed " << new_key;
  }
}

// An option's Check() names the C++ struct that holds it
// ("PnpRansacOptions.max_trials: ..."); a config's reader wants the JSON
// path it wrote ("registration.pnp.max_trials: ...").
std::string JsonKeysOfOptionError(std::string message) {
  static const std::pair<const char*, const char*> kSections[] = {
      {"RegistrationOptions.", "registration."},
      {"PnpRansacOptions.", "registration.pnp."},
      {"NndrMatcherOptions.", "registration.matching."},
      {"GuidedMatchingOptions.", "registration."},
      {"LocalBundleAdjustmentOptions.", "registration.bundle_adjustment."},
      {"LinkInformationOptions.", "registration.information."},
      {"LoopClosureOptions.", "loop_closure."},
      {"BayesFilterOptions.", "loop_closure.bayes."},
      {"VocabularyOptions.", "loop_closure.vocabulary."},
      {"DescriptorIndexOptions.", "loop_closure.vocabulary.index."},
      {"ProximityOptions.", "proximity."},
      {"PoseGraphOptimizerOptions.", "optimizer."},
      {"OdometryCacheOptions.", "localization."},
      {"EngineOptions.", ""}};
  for (const auto& [cpp, json] : kSections) {
    if (message.rfind(cpp, 0) == 0) return json + message.substr(std::strlen(cpp));
  }
  return message;
}

}  // namespace

EngineOptions ReadEngineOptions(JsonFields& fields) {
  RejectRenamedKeys(fields);
  EngineOptions o;
  JsonCodecReader::ReadFields(fields, &o);
  try {
    o.Check();
  } catch (const ConfigError& e) {
    SLAM_THROW(ConfigError) << fields.where() << ": " << JsonKeysOfOptionError(e.what());
  }
  return o;
}

EngineOptions ReadEngineOptionsFile(const std::string& path) {
  JsonFields fields(ReadJsonFile(path), path);
  return ReadEngineOptions(fields);
}

nlohmann::json EngineOptionsToJson(const EngineOptions& options) { return ToJsonObject(options); }

}  // namespace duskmap
