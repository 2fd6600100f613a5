// Reads LoopClosureOptions and ProximityOptions from JSON objects (strict:
// unknown keys are rejected with their path). Keys are the option field
// names; index kinds are strings ("kdtree", "bit_kdtree", "lsh",
// "hierarchical", "linear"). Absent keys keep their defaults.
//
//   {"vocabulary": {"nndr_ratio": 0.8, "max_features_per_node": 400,
//                   "index": {"binary_kind": "bit_kdtree", "checks": 32}},
//    "bayes": {"virtual_place_prior": 0.9}, "loop_threshold": 0.11}
#pragma once

#include <nlohmann/json.hpp>

#include "slam/core/json_fields.h"
#include "slam/retrieval/loop_closure_detector.h"
#include "slam/retrieval/proximity.h"

namespace duskmap {

// `where` names the object in errors, e.g. "configs/x.json:loop_closure".
LoopClosureOptions ReadLoopClosureOptions(const nlohmann::json& object, const std::string& where);
ProximityOptions ReadProximityOptions(const nlohmann::json& object, const std::string& where);

}  // namespace duskmap
