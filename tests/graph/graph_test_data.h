// Synthetic pose graphs with ground truth for graph tests and benchmarks:
// sessions driving around a circle, odometry with a yaw drift, and links.
#pragma once

#include <cmath>
#include <vector>

#include "slam/core/graph_types.h"
#include "slam/core/random.h"
#include "slam/core/rigid3.h"

namespace duskmap::testing {

// Ground-truth pose k of `count` on a circle of radius `radius_m`, heading along it.
inline Rigid3d CirclePose(int k, int count, double radius_m, double height_m = 0.0) {
  const double angle = 2.0 * M_PI * k / count;
  return Rigid3d(Eigen::Quaterniond(Eigen::AngleAxisd(angle + M_PI / 2, Eigen::Vector3d::UnitZ())),
                 Eigen::Vector3d(radius_m * std::cos(angle), radius_m * std::sin(angle), height_m));
}

inline Information6d DiagonalInformation(double sigma_m, double sigma_rad) {
  Information6d information = Information6d::Zero();
  information.diagonal() << Eigen::Vector3d::Constant(1.0 / (sigma_m * sigma_m)),
      Eigen::Vector3d::Constant(1.0 / (sigma_rad * sigma_rad));
  return information;
}

inline Link MakeLink(NodeId from, NodeId to, LinkType type, const Rigid3d& from_from_to,
                     const Information6d& information) {
  Link link;
  link.from = from;
  link.to = to;
  link.type = type;
  link.from_from_to = from_from_to;
  link.information = information;
  return link;
}

// Odometry measurement of a true relative motion with a yaw bias and noise.
inline Rigid3d DriftedMotion(const Rigid3d& truth, double yaw_bias_rad, double noise_m,
                             double noise_rad, Rng* rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  const Eigen::Vector3d rotation_noise(noise_rad * n(*rng), noise_rad * n(*rng),
                                       yaw_bias_rad + noise_rad * n(*rng));
  const Eigen::Quaterniond dq(Eigen::AngleAxisd(rotation_noise.norm(),
                                                rotation_noise.norm() > 0
                                                    ? rotation_noise.normalized()
                                                    : Eigen::Vector3d::UnitZ()));
  return Rigid3d(truth.rotation * dq,
                 truth.translation + Eigen::Vector3d(noise_m * n(*rng), noise_m * n(*rng),
                                                     noise_m * n(*rng)));
}

}  // namespace duskmap::testing
