#include "slam/datasets/camera_calibration.h"

#include <cmath>
#include <sstream>

#include <Eigen/Geometry>

#include "slam/core/check.h"

namespace duskmap {
namespace {

constexpr double kRotationTolerance = 1e-3;

}  // namespace

bool CameraCalibration::HasDistortion() const {
  for (double d : distortion) {
    if (d != 0.0) return true;
  }
  return false;
}

PinholeCamera CameraCalibration::Pinhole() const {
  PinholeCamera camera;
  camera.width = image_width;
  camera.height = image_height;
  if (projection) {
    camera.fx = (*projection)(0, 0);
    camera.fy = (*projection)(1, 1);
    camera.cx = (*projection)(0, 2);
    camera.cy = (*projection)(1, 2);
  } else {
    camera.fx = camera_matrix(0, 0);
    camera.fy = camera_matrix(1, 1);
    camera.cx = camera_matrix(0, 2);
    camera.cy = camera_matrix(1, 2);
  }
  return camera;
}

void CheckCalibration(const CameraCalibration& calibration, const std::string& where) {
  SLAM_THROW_IF_NOT(InputError, calibration.image_width > 0 && calibration.image_height > 0)
      << where << ": calibration image size " << calibration.image_width << "x"
      << calibration.image_height << " is not positive";
  SLAM_THROW_IF_NOT(InputError, calibration.camera_matrix.allFinite())
      << where << ": camera matrix has non-finite values";
  for (double d : calibration.distortion) {
    SLAM_THROW_IF_NOT(InputError, std::isfinite(d))
        << where << ": distortion has non-finite values";
  }
  SLAM_THROW_IF_NOT(InputError, !calibration.projection || calibration.projection->allFinite())
      << where << ": projection matrix has non-finite values";
  const PinholeCamera camera = calibration.Pinhole();
  SLAM_THROW_IF_NOT(InputError, camera.fx > 0.0 && camera.fy > 0.0)
      << where << ": focal lengths fx=" << camera.fx << " fy=" << camera.fy
      << " are not positive";
  SLAM_THROW_IF_NOT(InputError, calibration.body_from_camera.IsFinite())
      << where << ": local_transform has non-finite values";
}

PinholeCamera CameraForImage(const CameraCalibration& calibration, int width, int height,
                             const std::string& where) {
  const PinholeCamera camera = calibration.Pinhole();
  if (width == camera.width && height == camera.height) return camera;
  const double sx = static_cast<double>(width) / camera.width;
  const double sy = static_cast<double>(height) / camera.height;
  // Same aspect ratio: the scaled calibrated height is within one pixel.
  SLAM_THROW_IF_NOT(InputError, std::abs(camera.height * sx - height) <= 1.0)
      << where << ": calibration is for " << camera.width << "x" << camera.height
      << " but the image is " << width << "x" << height;
  PinholeCamera scaled = camera.Scaled(sx, sy);
  scaled.width = width;
  scaled.height = height;
  return scaled;
}

Rigid3d RigidFromRowMajor3x4(const double* values, const std::string& where) {
  Eigen::Matrix3d rotation;
  Eigen::Vector3d translation;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) rotation(r, c) = values[4 * r + c];
    translation(r) = values[4 * r + 3];
  }
  SLAM_THROW_IF_NOT(InputError, rotation.allFinite() && translation.allFinite())
      << where << ": transform has non-finite values";
  const double orthonormal_error =
      (rotation.transpose() * rotation - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  SLAM_THROW_IF_NOT(InputError,
                    orthonormal_error < kRotationTolerance && rotation.determinant() > 0.0)
      << where << ": transform rotation is not a rotation matrix (|R^T R - I| = "
      << orthonormal_error << ")";
  return Rigid3d(rotation, translation);
}

}  // namespace duskmap
