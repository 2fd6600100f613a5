#include "slam/synthetic/scene/scene.h"

#include <utility>

#include <cmath>

namespace duskmap {

double Quad::Intersect(const Eigen::Vector3d& from, const Eigen::Vector3d& direction) const {
  const Eigen::Vector3d n = normal();
  const double denom = n.dot(direction);
  if (std::abs(denom) < 1e-12) return -1.0;
  const double distance = n.dot(origin_in_world - from) / denom;
  if (distance <= 0.0) return -1.0;
  const Eigen::Vector3d offset = from + distance * direction - origin_in_world;
  const double s = offset.dot(u_axis);
  const double t = offset.dot(v_axis);
  if (s < 0.0 || t < 0.0 || s > size_u_m || t > size_v_m) return -1.0;
  return distance;
}

double Scene::FloorAreaM2() const {
  return (max_corner_xy - min_corner_xy).prod();
}

Eigen::Matrix3d CameraRotationFromYawPitchRoll(double yaw_rad, double pitch_rad, double roll_rad) {
  const Eigen::Vector3d forward(std::cos(yaw_rad) * std::cos(pitch_rad),
                                std::sin(yaw_rad) * std::cos(pitch_rad), std::sin(pitch_rad));
  const Eigen::Vector3d right0 = forward.cross(Eigen::Vector3d::UnitZ()).normalized();
  const Eigen::Vector3d down0 = forward.cross(right0);
  const double c = std::cos(roll_rad), s = std::sin(roll_rad);
  const Eigen::Vector3d right = c * right0 + s * down0;
  const Eigen::Vector3d down = forward.cross(right);
  Eigen::Matrix3d world_from_camera;
  world_from_camera.col(0) = right;
  world_from_camera.col(1) = down;
  world_from_camera.col(2) = forward;
  return world_from_camera;
}

void Scene::SetMeshes(std::vector<SceneMesh> new_meshes) {
  meshes = std::move(new_meshes);
  mesh_occluders = BuildMeshOccluders(meshes);
}

}  // namespace duskmap
