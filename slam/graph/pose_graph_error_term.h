// Ceres cost of one pose-graph link (after Ceres examples/slam/pose_graph_3d).
// With node poses (q_a, p_a) = world_from_a and (q_b, p_b) = world_from_b and
// the measured a_from_b = (q_ab, p_ab):
//   estimate:  q_ab_est = q_a^-1 q_b,   p_ab_est = q_a^-1 (p_b - p_a)
//   error:     [ p_ab_est - p_ab ;  2 vec(q_ab^-1 q_ab_est) ]
//   residual:  sqrt_information * error
// The error order (x, y, z, roll, pitch, yaw for small angles) matches the
// link information order, and sqrt_information^T sqrt_information =
// information, so the squared residual is the Mahalanobis error of the link.
#pragma once

#include <ceres/autodiff_cost_function.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "slam/core/rigid3.h"

namespace duskmap {

class RelativePoseError {
 public:
  RelativePoseError(const Rigid3d& a_from_b_measured,
                    const Eigen::Matrix<double, 6, 6>& sqrt_information)
      : measured_(a_from_b_measured), sqrt_information_(sqrt_information) {}

  template <typename T>
  bool operator()(const T* p_a_ptr, const T* q_a_ptr, const T* p_b_ptr, const T* q_b_ptr,
                  T* residuals_ptr) const {
    const Eigen::Map<const Eigen::Matrix<T, 3, 1>> p_a(p_a_ptr);
    const Eigen::Map<const Eigen::Quaternion<T>> q_a(q_a_ptr);
    const Eigen::Map<const Eigen::Matrix<T, 3, 1>> p_b(p_b_ptr);
    const Eigen::Map<const Eigen::Quaternion<T>> q_b(q_b_ptr);
    const Eigen::Quaternion<T> q_a_inverse = q_a.conjugate();
    const Eigen::Quaternion<T> q_ab_estimated = q_a_inverse * q_b;
    const Eigen::Matrix<T, 3, 1> p_ab_estimated = q_a_inverse * (p_b - p_a);
    const Eigen::Quaternion<T> delta_q =
        measured_.rotation.template cast<T>().conjugate() * q_ab_estimated;
    Eigen::Map<Eigen::Matrix<T, 6, 1>> residuals(residuals_ptr);
    residuals.template head<3>() = p_ab_estimated - measured_.translation.template cast<T>();
    residuals.template tail<3>() = T(2.0) * delta_q.vec();
    residuals.applyOnTheLeft(sqrt_information_.template cast<T>());
    return true;
  }

  static ceres::CostFunction* Create(const Rigid3d& a_from_b_measured,
                                     const Eigen::Matrix<double, 6, 6>& sqrt_information) {
    return new ceres::AutoDiffCostFunction<RelativePoseError, 6, 3, 4, 3, 4>(
        new RelativePoseError(a_from_b_measured, sqrt_information));
  }

 private:
  Rigid3d measured_;
  Eigen::Matrix<double, 6, 6> sqrt_information_;
};

}  // namespace duskmap
