#include "slam/synthetic/sensor/odometry.h"

#include <cmath>
#include <random>

#include "slam/core/check.h"
#include "slam/core/random.h"

namespace duskmap {

void OdometryOptions::Check() const {
  SLAM_THROW_IF_NOT(ConfigError, drift_fraction >= 0 && drift_fraction < 0.5)
      << "odometry.drift_fraction must be in [0, 0.5), got " << drift_fraction;
  SLAM_THROW_IF_NOT(ConfigError, scale_error_std >= 0 && scale_error_std < 0.2)
      << "odometry.scale_error_std must be in [0, 0.2), got " << scale_error_std;
  SLAM_THROW_IF_NOT(ConfigError, yaw_drift_deg_per_min >= 0 && yaw_drift_deg_per_min < 30)
      << "odometry.yaw_drift_deg_per_min must be in [0, 30), got " << yaw_drift_deg_per_min;
  SLAM_THROW_IF_NOT(ConfigError, yaw_noise_fraction >= 0 && yaw_noise_fraction < 0.5)
      << "odometry.yaw_noise_fraction must be in [0, 0.5), got " << yaw_noise_fraction;
}

std::vector<Rigid3d> SimulateOdometry(const OdometryOptions& options,
                                      const std::vector<Rigid3d>& world_from_camera,
                                      const std::vector<double>& times_s, uint64_t seed) {
  options.Check();
  SLAM_CHECK(world_from_camera.size() == times_s.size());
  std::vector<Rigid3d> odom_from_camera;
  if (world_from_camera.empty()) return odom_from_camera;
  Rng rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  const double scale = 1.0 + options.scale_error_std * normal(rng);
  const double yaw_rate_rad_s = options.yaw_drift_deg_per_min * normal(rng) * M_PI / 180.0 / 60.0;
  // Gravity ("up") in the odometry frame: the first camera's view of world +z.
  const Eigen::Vector3d up_in_odom = world_from_camera[0].rotation.conjugate() * Eigen::Vector3d::UnitZ();
  odom_from_camera.push_back(Rigid3d::Identity());
  for (size_t k = 1; k < world_from_camera.size(); ++k) {
    const Rigid3d delta = world_from_camera[k - 1].Inverse() * world_from_camera[k];
    const double distance = delta.translation.norm();
    const double turned = Eigen::AngleAxisd(delta.rotation).angle();
    Eigen::Vector3d noisy_t = delta.translation * scale;
    const double sigma = options.drift_fraction * distance;
    for (int i = 0; i < 3; ++i) noisy_t[i] += sigma * normal(rng);
    const double yaw_error = yaw_rate_rad_s * (times_s[k] - times_s[k - 1]) +
                             options.yaw_noise_fraction * turned * normal(rng);
    const Rigid3d& previous = odom_from_camera.back();
    Rigid3d next = previous * Rigid3d(delta.rotation, noisy_t);
    // Yaw drift: rotate the new pose about gravity through the previous position.
    const Eigen::Quaterniond yaw(Eigen::AngleAxisd(yaw_error, up_in_odom));
    next = Rigid3d(yaw * next.rotation, previous.translation + yaw * (next.translation - previous.translation));
    odom_from_camera.push_back(next);
  }
  return odom_from_camera;
}

}  // namespace duskmap
