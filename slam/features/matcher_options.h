// Which descriptor matcher registration uses, and its construction:
// "nndr" (registration's nearest-neighbour ratio matcher, configured by
// RegistrationOptions.matching) or "superglue" (SuperGlueMatcher; needs
// SuperPoint features). JSON: {"type": "superglue",
// "superglue": {"model_path": "models/superglue_indoor.onnx", "match_threshold": 0.2}}.
#pragma once

#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "slam/core/json_fields.h"
#include "slam/features/feature_matcher.h"
#include "slam/features/superglue.h"

namespace duskmap {

struct MatcherOptions {
  std::string type = "nndr";  // "nndr" or "superglue" (Vis/CorNNType 1 or 6)
  SuperGlueOptions superglue;
  void Check() const;
  // Whether the matcher reads the keypoints' responses (SuperGlue's scores);
  // NNDR does not, so a map loaded for it can leave them out.
  bool ReadsKeypointResponses() const { return type == "superglue"; }
};


// The matcher to hand to EstimateTransform: nullptr for "nndr" (registration
// then builds its own NNDR matcher), a loaded SuperGlueMatcher for
// "superglue" (throws InputError when its model is missing or wrong).
std::unique_ptr<FeatureMatcher> CreateFeatureMatcher(const MatcherOptions& options);

}  // namespace duskmap
