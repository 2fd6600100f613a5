// Odometry like visual-inertial odometry: each session has its own odometry
// frame (identity at the first frame); the motion between frames is the true
// motion with a per-session scale error, random-walk translation noise
// proportional to the distance travelled and a slow yaw drift about gravity.
#pragma once

#include <cstdint>
#include <vector>

#include "slam/core/rigid3.h"

namespace duskmap {

struct OdometryOptions {
  double drift_fraction = 0.01;          // translation error std per metre travelled (1%)
  double scale_error_std = 0.005;        // per-session scale error std
  double yaw_drift_deg_per_min = 0.6;    // std of the per-session constant yaw drift rate
  double yaw_noise_fraction = 0.005;     // yaw error std per radian turned

  void Check() const;
};

// odom_from_camera for each ground-truth pose (body = camera for the
// synthetic sensor). `times_s` are the frame times in seconds.
std::vector<Rigid3d> SimulateOdometry(const OdometryOptions& options,
                                      const std::vector<Rigid3d>& world_from_camera,
                                      const std::vector<double>& times_s, uint64_t seed);

}  // namespace duskmap
