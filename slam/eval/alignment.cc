#include "slam/eval/alignment.h"

#include <cmath>

#include <Eigen/SVD>

#include "slam/core/check.h"

namespace duskmap {

void AlignmentOptions::Check() const {
  SLAM_THROW_IF_NOT(ConfigError, min_points >= 3)
      << "AlignmentOptions.min_points: must be >= 3, got " << min_points;
}

namespace {

void CheckInputs(const std::vector<Eigen::Vector3d>& source,
                 const std::vector<Eigen::Vector3d>& target, const AlignmentOptions& options) {
  SLAM_THROW_IF_NOT(InputError, source.size() == target.size())
      << "AlignPoints: " << source.size() << " source points but " << target.size()
      << " target points";
  SLAM_THROW_IF_NOT(InputError, source.size() >= options.min_points)
      << "AlignPoints: " << source.size() << " correspondences, need at least "
      << options.min_points;
  for (size_t i = 0; i < source.size(); ++i) {
    SLAM_THROW_IF_NOT(InputError, source[i].allFinite() && target[i].allFinite())
        << "AlignPoints: correspondence " << i << " is not finite";
  }
}

}  // namespace

AlignmentResult AlignPoints(const std::vector<Eigen::Vector3d>& source,
                            const std::vector<Eigen::Vector3d>& target,
                            const AlignmentOptions& options) {
  options.Check();
  CheckInputs(source, target, options);
  const size_t n = source.size();
  Eigen::Vector3d mean_source = Eigen::Vector3d::Zero();
  Eigen::Vector3d mean_target = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < n; ++i) {
    mean_source += source[i];
    mean_target += target[i];
  }
  mean_source /= static_cast<double>(n);
  mean_target /= static_cast<double>(n);

  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();  // sum (t - mt)(s - ms)^T / n
  double source_variance = 0.0;
  for (size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d ds = source[i] - mean_source;
    covariance += (target[i] - mean_target) * ds.transpose();
    source_variance += ds.squaredNorm();
  }
  covariance /= static_cast<double>(n);
  source_variance /= static_cast<double>(n);

  Eigen::JacobiSVD<Eigen::Matrix3d> svd(covariance, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::Vector3d singular = svd.singularValues();
  SLAM_THROW_IF_NOT(InputError, source_variance > 1e-18 && singular(1) > 1e-9 * singular(0))
      << "AlignPoints: degenerate point set (all " << n
      << " points coincide or are collinear), rotation undetermined";
  Eigen::Matrix3d sign = Eigen::Matrix3d::Identity();
  if (svd.matrixU().determinant() * svd.matrixV().determinant() < 0.0) sign(2, 2) = -1.0;
  const Eigen::Matrix3d rotation = svd.matrixU() * sign * svd.matrixV().transpose();
  const double scale =
      options.estimate_scale ? (singular.asDiagonal() * sign).trace() / source_variance : 1.0;

  AlignmentResult result;
  result.scale = scale;
  result.target_from_source = Rigid3d(rotation, mean_target - scale * rotation * mean_source);
  result.num_points = n;
  double sum_sq = 0.0;
  for (size_t i = 0; i < n; ++i) sum_sq += (target[i] - result.Apply(source[i])).squaredNorm();
  result.rmse_m = std::sqrt(sum_sq / static_cast<double>(n));
  return result;
}

}  // namespace duskmap
