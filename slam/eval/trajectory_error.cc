#include "slam/eval/trajectory_error.h"

#include <algorithm>
#include <cmath>

#include "slam/core/check.h"

namespace duskmap {

AteResult ComputeAte(const std::vector<Rigid3d>& estimated,
                     const std::vector<Rigid3d>& ground_truth, const AlignmentOptions& options) {
  SLAM_THROW_IF_NOT(InputError, estimated.size() == ground_truth.size())
      << "ComputeAte: " << estimated.size() << " estimated poses but " << ground_truth.size()
      << " ground-truth poses";
  std::vector<Eigen::Vector3d> source, target;
  source.reserve(estimated.size());
  target.reserve(estimated.size());
  for (size_t i = 0; i < estimated.size(); ++i) {
    source.push_back(estimated[i].translation);
    target.push_back(ground_truth[i].translation);
  }
  AteResult result;
  result.alignment = AlignPoints(source, target, options);
  result.num_poses = source.size();
  std::vector<double> errors(source.size());
  double sum = 0.0, sum_sq = 0.0;
  for (size_t i = 0; i < source.size(); ++i) {
    errors[i] = (target[i] - result.alignment.Apply(source[i])).norm();
    sum += errors[i];
    sum_sq += errors[i] * errors[i];
  }
  const double n = static_cast<double>(errors.size());
  result.rmse_m = std::sqrt(sum_sq / n);
  result.mean_m = sum / n;
  result.max_m = *std::max_element(errors.begin(), errors.end());
  std::sort(errors.begin(), errors.end());
  const size_t mid = errors.size() / 2;
  result.median_m = errors.size() % 2 ? errors[mid] : 0.5 * (errors[mid - 1] + errors[mid]);
  return result;
}

}  // namespace duskmap
