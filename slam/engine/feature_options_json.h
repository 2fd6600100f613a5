// Every parameter of a FeatureOptions as JSON, in the layout
// ReadFeatureOptions reads, so a map records exactly how its features were
// made (and the options can be read back from the map). Lives here because
// the features module has no writer yet (see docs/engine.md).
#pragma once

#include <nlohmann/json.hpp>

#include "slam/features/feature_options.h"

namespace duskmap {

nlohmann::json FeatureOptionsToJson(const FeatureOptions& options);

}  // namespace duskmap
