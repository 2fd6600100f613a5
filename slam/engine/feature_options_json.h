// Every parameter of a FeatureOptions as JSON, in the layout
// ReadFeatureOptions reads, so a map records exactly how its features were
// made (and the options can be read back from the map). Lives here because
// the features module has no writer yet (see docs/engine.md).
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "slam/features/feature_options.h"

namespace duskmap {

nlohmann::json FeatureOptionsToJson(const FeatureOptions& options);

// The feature options a map was built with, read back from its metadata's
// feature_parameters_json (keys a map of an older version lacks keep their
// defaults); ConfigError naming `map_path` when the text is not such JSON.
FeatureOptions FeatureOptionsOfMap(const std::string& feature_parameters_json,
                                   const std::string& map_path);

}  // namespace duskmap
