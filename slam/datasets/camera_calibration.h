// The calibration of one RTAB-Map camera, as stored in a database blob or in
// the export's per-image YAML: intrinsics for image_width x image_height,
// optional distortion / rectification / projection, and the camera-to-body
// `local_transform`.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "slam/core/camera.h"
#include "slam/core/rigid3.h"

namespace duskmap {

struct CameraCalibration {
  std::string name;       // camera_name (the export writes the image stem)
  int image_width = 0;    // pixels; 0 when not stored
  int image_height = 0;   // pixels; 0 when not stored
  Eigen::Matrix3d camera_matrix = Eigen::Matrix3d::Zero();  // K
  // Distortion in OpenCV order: plumb_bob / rational_polynomial coefficients
  // (k1 k2 p1 p2 [k3 ...]) or, when fisheye, k1 k2 k3 k4.
  std::vector<double> distortion;
  bool fisheye = false;
  std::optional<Eigen::Matrix3d> rectification;           // R
  std::optional<Eigen::Matrix<double, 3, 4>> projection;  // P (rectified camera)
  Rigid3d body_from_camera;                                // local_transform

  bool HasDistortion() const;
  // Intrinsics of the (undistorted, rectified) image at the calibrated size:
  // from P when present, else from K.
  PinholeCamera Pinhole() const;
};

// Throws InputError "<where>: <problem>" when K is not a valid pinhole matrix,
// the size is not positive or a value is not finite.
void CheckCalibration(const CameraCalibration& calibration, const std::string& where);

// Intrinsics for an image of width x height: the calibrated intrinsics, scaled
// when the image is a uniformly resized version of the calibrated size (same
// aspect ratio within one pixel). Throws InputError naming `where` otherwise.
PinholeCamera CameraForImage(const CameraCalibration& calibration, int width, int height,
                             const std::string& where);

// A row-major 3x4 [R | t] as a Rigid3d; throws InputError "<where>: ..." when
// a value is not finite or R is not a rotation (tolerance 1e-3).
Rigid3d RigidFromRowMajor3x4(const double* values, const std::string& where);

}  // namespace duskmap
