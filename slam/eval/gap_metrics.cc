#include "slam/eval/gap_metrics.h"

#include <algorithm>

#include "slam/core/check.h"

namespace duskmap {

void GapMetricsOptions::Check() const {
  SLAM_THROW_IF_NOT(ConfigError, within_m > 0.0)
      << "GapMetricsOptions.within_m: must be > 0, got " << within_m;
}

GapMetrics ComputeGapMetrics(const std::vector<Eigen::Vector3d>& positions,
                             const std::vector<bool>& relocalized,
                             const GapMetricsOptions& options) {
  options.Check();
  SLAM_THROW_IF_NOT(InputError, positions.size() == relocalized.size())
      << "ComputeGapMetrics: " << positions.size() << " positions but " << relocalized.size()
      << " re-localization flags";
  GapMetrics metrics;
  metrics.distance_since_last_m.resize(positions.size(), 0.0);
  double since_last_m = 0.0;
  for (size_t i = 0; i < positions.size(); ++i) {
    SLAM_THROW_IF_NOT(InputError, positions[i].allFinite())
        << "ComputeGapMetrics: position " << i << " is not finite";
    double step_m = 0.0;
    if (i > 0) {
      step_m = (positions[i] - positions[i - 1]).norm();
      since_last_m += step_m;
      metrics.total_distance_m += step_m;
    }
    if (step_m <= options.within_m) ++metrics.num_within_bound;
    metrics.max_gap_m = std::max(metrics.max_gap_m, since_last_m);
    if (relocalized[i]) {
      ++metrics.num_relocalized;
      if (since_last_m <= options.within_m) ++metrics.num_within;
      since_last_m = 0.0;
    }
    metrics.distance_since_last_m[i] = since_last_m;
  }
  if (!positions.empty()) metrics.within_pct = 100.0 * metrics.num_within / positions.size();
  return metrics;
}

}  // namespace duskmap
