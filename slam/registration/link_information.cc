#include "slam/registration/link_information.h"

#include <algorithm>
#include <cmath>

#include "slam/core/check.h"

namespace duskmap {
namespace {

constexpr double kMadToVariance = 2.1981;  // the reference's scale on the percentile

double AngleBetween(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const double norms = a.norm() * b.norm();
  if (!(norms > 0.0)) return 0.0;
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

double Percentile(std::vector<double>* values, int ratio) {
  const size_t index = values->size() / static_cast<size_t>(ratio);
  std::nth_element(values->begin(), values->begin() + index, values->end());
  return (*values)[index];
}

}  // namespace

void LinkInformationOptions::Check() const {
  SLAM_THROW_IF_NOT(ConfigError, variance_median_ratio >= 1)
      << "LinkInformationOptions.variance_median_ratio: must be >= 1, got "
      << variance_median_ratio;
  SLAM_THROW_IF_NOT(ConfigError, missing_depth_scale > 0.0)
      << "LinkInformationOptions.missing_depth_scale: must be > 0, got " << missing_depth_scale;
  SLAM_THROW_IF_NOT(ConfigError, min_linear_variance_m2 > 0.0)
      << "LinkInformationOptions.min_linear_variance_m2: must be > 0, got "
      << min_linear_variance_m2;
  SLAM_THROW_IF_NOT(ConfigError, min_angular_variance_rad2 > 0.0)
      << "LinkInformationOptions.min_angular_variance_rad2: must be > 0, got "
      << min_angular_variance_rad2;
  SLAM_THROW_IF_NOT(ConfigError, max_linear_variance_m2 >= 0.0)
      << "LinkInformationOptions.max_linear_variance_m2: must be >= 0, got "
      << max_linear_variance_m2;
}

LinkCovariance ComputeLinkInformation(const LinkInformationOptions& options,
                                      const std::vector<InlierCorrespondence>& inliers,
                                      const PinholeCamera& query_camera,
                                      const Rigid3d& node_from_query) {
  options.Check();
  SLAM_CHECK(!inliers.empty());
  SLAM_CHECK(node_from_query.IsFinite());
  const Rigid3d query_from_node = node_from_query.Inverse();
  std::vector<double> squared_errors, angles;
  squared_errors.reserve(inliers.size());
  angles.reserve(inliers.size());
  for (const InlierCorrespondence& c : inliers) {
    Eigen::Vector3d q_in_node;
    if (c.point_in_query.allFinite()) {
      q_in_node = node_from_query * c.point_in_query;
    } else {
      const double depth = (query_from_node * c.point_in_node).z() * options.missing_depth_scale;
      q_in_node = node_from_query *
                  query_camera.Unproject(c.pixel_in_query.x(), c.pixel_in_query.y(), depth);
    }
    squared_errors.push_back((c.point_in_node - q_in_node).squaredNorm());
    angles.push_back(AngleBetween(c.point_in_node, q_in_node));
  }
  LinkCovariance result;
  result.linear_variance_m2 =
      std::max(options.min_linear_variance_m2,
               kMadToVariance * Percentile(&squared_errors, options.variance_median_ratio));
  result.angular_variance =
      std::max(options.min_angular_variance_rad2,
               kMadToVariance * Percentile(&angles, options.variance_median_ratio));
  result.information.setZero();
  result.information.diagonal().head<3>().setConstant(1.0 / result.linear_variance_m2);
  result.information.diagonal().tail<3>().setConstant(1.0 / result.angular_variance);
  return result;
}

}  // namespace duskmap
