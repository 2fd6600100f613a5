// Rigid 3D transform. Naming convention: a Rigid3d called b_from_a maps
// coordinates in frame a to frame b:  x_in_b = b_from_a * x_in_a
//                                            = rotation * x_in_a + translation.
// Compose as c_from_a = c_from_b * b_from_a.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <ostream>

namespace duskmap {

struct Rigid3d {
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();

  Rigid3d() = default;
  Rigid3d(const Eigen::Quaterniond& r, const Eigen::Vector3d& t)
      : rotation(r.normalized()), translation(t) {}
  Rigid3d(const Eigen::Matrix3d& r, const Eigen::Vector3d& t)
      : rotation(Eigen::Quaterniond(r).normalized()), translation(t) {}

  static Rigid3d Identity() { return Rigid3d(); }
  // From a 3x4 or 4x4 matrix [R | t].
  static Rigid3d FromMatrix(const Eigen::Matrix4d& m) {
    return Rigid3d(Eigen::Matrix3d(m.topLeftCorner<3, 3>()), m.topRightCorner<3, 1>());
  }

  Rigid3d Inverse() const {
    const Eigen::Quaterniond inv = rotation.conjugate();
    return Rigid3d(inv, -(inv * translation));
  }
  Eigen::Matrix4d ToMatrix() const {
    Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
    m.topLeftCorner<3, 3>() = rotation.toRotationMatrix();
    m.topRightCorner<3, 1>() = translation;
    return m;
  }
  Eigen::Vector3d operator*(const Eigen::Vector3d& x) const {
    return rotation * x + translation;
  }
  Rigid3d operator*(const Rigid3d& other) const {
    return Rigid3d(rotation * other.rotation, rotation * other.translation + translation);
  }
  bool IsFinite() const {
    return rotation.coeffs().allFinite() && translation.allFinite();
  }
};

// Angle of the relative rotation between a and b, in radians, in [0, pi].
inline double RotationAngleRad(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) {
  return a.angularDistance(b);
}

inline std::ostream& operator<<(std::ostream& os, const Rigid3d& t) {
  return os << "Rigid3d(t=[" << t.translation.transpose() << "], q(xyzw)=["
            << t.rotation.coeffs().transpose() << "])";
}

}  // namespace duskmap
