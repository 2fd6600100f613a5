// Reads PoseGraphOptimizerOptions from a JSON object (strict: unknown keys
// throw ConfigError with their path):
//   {"max_iterations": 20, "function_tolerance": 1e-6,
//    "robust_loss": "none|huber|cauchy", "robust_loss_scale": 1.0,
//    "max_error_ratio": 3.0, "initialize_from_links": true, "num_threads": 1}
#pragma once

#include "slam/core/json_fields.h"
#include "slam/graph/pose_graph_optimizer.h"

namespace duskmap {

PoseGraphOptimizerOptions ReadPoseGraphOptimizerOptions(JsonFields& fields);

}  // namespace duskmap
