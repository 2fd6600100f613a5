// Builds the extractor of a feature type (feature_registry.h) from its
// options: the one place that knows every extractor class.
#pragma once

#include <memory>

#include "slam/features/feature_extractor.h"
#include "slam/features/feature_options.h"

namespace duskmap {

// Builds the extractor named by options.type with its options; ConfigError
// for an unknown type or bad options (FeatureOptions::Check).
std::unique_ptr<FeatureExtractor> CreateFeatureExtractor(const FeatureOptions& options);

}  // namespace duskmap
