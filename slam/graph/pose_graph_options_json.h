// JSON codec of the pose-graph optimiser's options (slam/core/json_codec.h):
//   {"max_iterations": 20, "function_tolerance": 1e-6,
//    "robust_loss": "none|huber|cauchy", "robust_loss_scale": 1.0,
//    "max_error_ratio": 3.0, "initialization": "every_optimization|when_components_join|never",
//    "sparse_linear_algebra": "eigen_sparse|suite_sparse",
//    "num_threads": 1}
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
struct JsonEnumNames<PoseInitialization> {
  static constexpr std::pair<PoseInitialization, const char*> kNames[] = {
      {PoseInitialization::kEveryOptimization, "every_optimization"},
      {PoseInitialization::kWhenComponentsJoin, "when_components_join"},
      {PoseInitialization::kNever, "never"}};
};

template <>
struct JsonEnumNames<SparseLinearAlgebra> {
  static constexpr std::pair<SparseLinearAlgebra, const char*> kNames[] = {
      {SparseLinearAlgebra::kEigenSparse, "eigen_sparse"},
      {SparseLinearAlgebra::kSuiteSparse, "suite_sparse"}};
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
    f("initialization", o.initialization);
    f("sparse_linear_algebra", o.sparse_linear_algebra);
    f("num_threads", o.num_threads);
  }
};

}  // namespace duskmap
