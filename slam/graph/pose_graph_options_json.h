// JSON codec of the pose-graph optimiser's options (slam/core/json_codec.h):
//   {"max_iterations": 20, "function_tolerance": 1e-6,
//    "robust_loss": "none|huber|cauchy", "robust_loss_scale": 1.0,
//    "max_error_ratio": 3.0, "initialize_from_links": true, "num_threads": 1}
#pragma once

#include <utility>

#include "slam/core/json_codec.h"
#include "slam/graph/pose_graph_optimizer.h"

namespace duskmap {

template <>
struct JsonEnumNames<RobustLoss> {
  static constexpr std::pair<RobustLoss, const char*> kNames[] = {
      {RobustLoss::kNone, "none"}, {RobustLoss::kHuber, "huber"}, {RobustLoss::kCauchy, "cauchy"}};
};

template <>
struct JsonCodec<PoseGraphOptimizerOptions> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    f("max_iterations", o.max_iterations);
    f("function_tolerance", o.function_tolerance);
    f("robust_loss", o.robust_loss);
    f("robust_loss_scale", o.robust_loss_scale);
    f("max_error_ratio", o.max_error_ratio);
    f("initialize_from_links", o.initialize_from_links);
    f("num_threads", o.num_threads);
  }
};

}  // namespace duskmap
