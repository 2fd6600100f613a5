#include "slam/features/feature_options_json.h"

#include "slam/core/check.h"
#include "slam/core/json_fields.h"

namespace duskmap {

FeatureOptions FeatureOptionsOfMap(const std::string& feature_parameters_json,
                                   const std::string& map_path) {
  const std::string where = map_path + ": feature_parameters";
  nlohmann::json json;
  try {
    json = ParseJsonText(feature_parameters_json, where);
  } catch (const ConfigError&) {  // duskmap wrote it: any problem is damage
    SLAM_THROW(ConfigError) << where << ": not JSON (the map is damaged; rebuild it)";
  }
  SLAM_THROW_IF_NOT(ConfigError, json.is_object()) << where << ": not a JSON object (rebuild the map)";
  return ReadJsonOptions<FeatureOptions>(json, where);
}

}  // namespace duskmap
