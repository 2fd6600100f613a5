// Pinhole camera without distortion (images are undistorted by the reader).
// Camera frame: x right, y down, z forward (OpenCV convention).
#pragma once

#include <Eigen/Core>
#include <cmath>

namespace duskmap {

struct PinholeCamera {
  int width = 0;
  int height = 0;
  double fx = 0.0;
  double fy = 0.0;
  double cx = 0.0;
  double cy = 0.0;

  bool IsValid() const { return width > 0 && height > 0 && fx > 0.0 && fy > 0.0; }

  // Projects a point in the camera frame; returns false when behind the camera.
  bool Project(const Eigen::Vector3d& point_in_camera, Eigen::Vector2d* pixel) const {
    if (!(point_in_camera.z() > 0.0)) return false;
    *pixel = Eigen::Vector2d(fx * point_in_camera.x() / point_in_camera.z() + cx,
                             fy * point_in_camera.y() / point_in_camera.z() + cy);
    return true;
  }
  // Back-projects pixel (u, v) with depth along the optical axis, in metres.
  Eigen::Vector3d Unproject(double u, double v, double depth_m) const {
    return Eigen::Vector3d((u - cx) / fx * depth_m, (v - cy) / fy * depth_m, depth_m);
  }
  bool InImage(double u, double v) const {
    return u >= 0.0 && v >= 0.0 && u < width && v < height;
  }
  // The same camera for an image resized by (sx, sy).
  PinholeCamera Scaled(double sx, double sy) const {
    PinholeCamera c = *this;
    c.width = static_cast<int>(std::lround(width * sx));
    c.height = static_cast<int>(std::lround(height * sy));
    c.fx *= sx;
    c.fy *= sy;
    c.cx = (cx + 0.5) * sx - 0.5;
    c.cy = (cy + 0.5) * sy - 0.5;
    return c;
  }
};

}  // namespace duskmap
