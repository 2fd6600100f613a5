#include "slam/engine/engine_options.h"

#include <cstring>
#include <utility>

#include <optional>

#include "slam/core/check.h"

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
  SLAM_THROW_IF_NOT(ConfigError, matcher.type != "superglue" || features.type == "superpoint")
      << "EngineOptions.matcher.type: superglue needs features.type superpoint, got "
      << features.type;
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

// A DescriptorStorage option ("float32" or "uint8") under `key`; `field`
// names it in the error.
void ReadStorage(JsonFields& fields, const char* key, const char* field, DescriptorStorage* out) {
  std::string name = DescriptorStorageName(*out);
  fields.Read(key, &name);
  const std::optional<DescriptorStorage> storage = DescriptorStorageFromName(name);
  SLAM_THROW_IF_NOT(ConfigError, storage.has_value())
      << "EngineOptions." << field << ": must be \"float32\" or \"uint8\", got \"" << name << "\"";
  *out = *storage;
}

// An option's Check() names the C++ struct that holds it
// ("RegistrationOptions.guess_window_px: ..."); a config's reader wants the
// JSON section it wrote ("registration.guess_window_px: ...").
std::string JsonKeysOfOptionError(std::string message) {
  static const std::pair<const char*, const char*> kSections[] = {
      {"RegistrationOptions.", "registration."},
      {"PnpRansacOptions.", "registration."},
      {"NndrMatcherOptions.", "registration."},
      {"GuidedMatchingOptions.", "registration."},
      {"LoopClosureOptions.", "loop_closure."},
      {"BayesFilterOptions.", "loop_closure."},
      {"VocabularyOptions.", "loop_closure."},
      {"DescriptorIndexOptions.", "loop_closure."},
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
  EngineOptions o;
  JsonFields features = fields.Child("features");
  o.features = ReadFeatureOptions(features);
  JsonFields registration = fields.Child("registration");
  registration.Read("min_inliers", &o.registration.min_inliers);
  registration.Read("second_pass", &o.registration.second_pass);
  registration.Read("guess_window_px", &o.registration.guess_window_px);
  registration.Read("float_nndr_ratio", &o.registration.matching.float_ratio);
  registration.Read("binary_nndr_ratio", &o.registration.matching.binary_ratio);
  registration.Read("max_reprojection_error_px", &o.registration.pnp.max_reprojection_error_px);
  registration.RejectUnknown();
  JsonFields matcher = fields.Child("matcher");
  o.matcher = ReadMatcherOptions(matcher);
  JsonFields lcd = fields.Child("loop_closure");
  lcd.Read("loop_threshold", &o.loop_closure.loop_threshold);
  lcd.Read("aggressive_loop_threshold", &o.loop_closure.aggressive_loop_threshold);
  lcd.Read("bad_signature_ratio", &o.loop_closure.vocabulary.bad_signature_ratio);
  ReadStorage(lcd, "word_storage", "loop_closure.word_storage",
              &o.loop_closure.vocabulary.index.float_storage);
  lcd.RejectUnknown();
  JsonFields proximity = fields.Child("proximity");
  proximity.Read("local_radius_m", &o.proximity.local_radius_m);
  proximity.Read("max_angle_deg", &o.proximity.max_angle_deg);
  proximity.RejectUnknown();
  JsonFields optimizer = fields.Child("optimizer");
  optimizer.Read("max_iterations", &o.optimizer.max_iterations);
  optimizer.Read("max_error_ratio", &o.optimizer.max_error_ratio);
  optimizer.RejectUnknown();
  JsonFields odometry = fields.Child("odometry");
  odometry.Read("linear_sigma_m", &o.odometry.linear_sigma_m);
  odometry.Read("angular_sigma_rad", &o.odometry.angular_sigma_rad);
  odometry.RejectUnknown();
  JsonFields mapping = fields.Child("mapping");
  mapping.Read("proximity", &o.mapping.proximity);
  mapping.Read("proximity_max_paths", &o.mapping.proximity_max_paths);
  mapping.Read("reduce_graph", &o.mapping.reduce_graph);
  mapping.Read("short_term_memory", &o.mapping.short_term_memory);
  ReadStorage(mapping, "descriptor_storage", "mapping.descriptor_storage",
              &o.mapping.descriptor_storage);
  mapping.RejectUnknown();
  JsonFields localization = fields.Child("localization");
  localization.Read("proximity", &o.localization.proximity);
  localization.Read("proximity_max_paths", &o.localization.proximity_max_paths);
  localization.Read("odometry_cache_size", &o.localization.odometry_cache_size);
  localization.Read("odometry_cache_max_error_ratio",
                    &o.localization.odometry_cache_max_error_ratio);
  localization.RejectUnknown();
  fields.Read("random_seed", &o.random_seed);
  std::string binary_distance = BinaryDistanceName(o.binary_distance);
  fields.Read("binary_distance", &binary_distance);
  o.binary_distance = ParseBinaryDistance(binary_distance, "EngineOptions.binary_distance");
  fields.RejectUnknown();
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

nlohmann::json EngineOptionsToJson(const EngineOptions& o) {
  return {
      {"registration",
       {{"min_inliers", o.registration.min_inliers},
        {"second_pass", o.registration.second_pass},
        {"guess_window_px", o.registration.guess_window_px},
        {"float_nndr_ratio", o.registration.matching.float_ratio},
        {"binary_nndr_ratio", o.registration.matching.binary_ratio},
        {"max_reprojection_error_px", o.registration.pnp.max_reprojection_error_px}}},
      {"matcher", MatcherOptionsToJson(o.matcher)},
      {"loop_closure",
       {{"loop_threshold", o.loop_closure.loop_threshold},
        {"aggressive_loop_threshold", o.loop_closure.aggressive_loop_threshold},
        {"bad_signature_ratio", o.loop_closure.vocabulary.bad_signature_ratio},
        {"word_storage", DescriptorStorageName(o.loop_closure.vocabulary.index.float_storage)}}},
      {"proximity",
       {{"local_radius_m", o.proximity.local_radius_m},
        {"max_angle_deg", o.proximity.max_angle_deg}}},
      {"optimizer",
       {{"max_iterations", o.optimizer.max_iterations},
        {"max_error_ratio", o.optimizer.max_error_ratio}}},
      {"odometry",
       {{"linear_sigma_m", o.odometry.linear_sigma_m},
        {"angular_sigma_rad", o.odometry.angular_sigma_rad}}},
      {"mapping",
       {{"proximity", o.mapping.proximity},
        {"proximity_max_paths", o.mapping.proximity_max_paths},
        {"reduce_graph", o.mapping.reduce_graph},
        {"short_term_memory", o.mapping.short_term_memory},
        {"descriptor_storage", DescriptorStorageName(o.mapping.descriptor_storage)}}},
      {"localization",
       {{"proximity", o.localization.proximity},
        {"proximity_max_paths", o.localization.proximity_max_paths},
        {"odometry_cache_size", o.localization.odometry_cache_size},
        {"odometry_cache_max_error_ratio", o.localization.odometry_cache_max_error_ratio}}},
      {"random_seed", o.random_seed},
      {"binary_distance", BinaryDistanceName(o.binary_distance)}};
}

}  // namespace duskmap
