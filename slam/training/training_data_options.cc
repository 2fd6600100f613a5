#include "slam/training/training_data_options.h"

#include <cmath>
#include <functional>

#include "slam/core/check.h"
#include "slam/core/json_reader.h"
#include "slam/training/training_data_options_json.h"

namespace duskmap {
namespace {

// Runs a nested struct's check with its key in front of the message.
void CheckNested(const char* key, const std::function<void()>& check) {
  try {
    check();
  } catch (const ConfigError& e) {
    SLAM_THROW(ConfigError) << key << "." << e.what();
  }
}

}  // namespace

void TrainingDataOptions::Check() const {
  CheckNested("scenes", [this] { scenes.Check(); });
  CheckNested("patch", [this] { patch.Check(); });
  Correspondence().Check();
  SLAM_THROW_IF_NOT(ConfigError, max_pairs_per_image_pair >= 1)
      << "max_pairs_per_image_pair: must be >= 1, got " << max_pairs_per_image_pair;
  SLAM_THROW_IF_NOT(ConfigError, std::isfinite(same_time_share) && same_time_share >= 0.0 && same_time_share <= 1.0)
      << "same_time_share: must be in [0, 1], got " << same_time_share;
  SLAM_THROW_IF_NOT(ConfigError, validation_scenes >= 0 && validation_scenes < scenes.scenes)
      << "validation_scenes: must be in [0, scenes.scenes - 1] (some scenes train), got " << validation_scenes;
  SLAM_THROW_IF_NOT(ConfigError, threads >= 1) << "threads: must be >= 1, got " << threads;
}

CorrespondenceOptions TrainingDataOptions::Correspondence() const {
  CorrespondenceOptions options;
  options.max_offset_px = max_offset_px;
  options.max_scale_ratio = max_scale_ratio;
  options.max_angle_deg = max_angle_deg;
  options.occlusion_tolerance = occlusion_tolerance;
  return options;
}

TrainingDataOptions ReadTrainingDataConfig(const std::string& path) {
  const nlohmann::json json = ReadJsonFile(path);
  SLAM_THROW_IF_NOT(ConfigError, json.is_object()) << path << ": expected a JSON object";
  for (const auto& item : json.items()) {
    SLAM_THROW_IF_NOT(ConfigError, item.key() == "data" || item.key() == "train" || item.key() == "_comment")
        << path << ": unknown key '" << item.key() << "' (expected data, train, _comment)";
  }
  SLAM_THROW_IF_NOT(ConfigError, json.contains("data")) << path << ": missing key 'data'";
  SLAM_THROW_IF_NOT(ConfigError, json.at("data").is_object()) << path << ":data: expected a JSON object";
  return ReadJsonOptions<TrainingDataOptions>(json.at("data"), path + ":data");
}

}  // namespace duskmap
