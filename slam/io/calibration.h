// The calibration file of a TUM-layout session (calibration.json): pinhole
// intrinsics and the depth-image scale (raw units per metre: 1000 for the
// synthetic millimetres, 5000 for TUM RGB-D). Real TUM sequences have none;
// their intrinsics come from the published freiburg1/2/3 values.
#pragma once

#include <string>

#include "slam/core/camera.h"

namespace duskmap {

struct TumCalibration {
  PinholeCamera camera;
  double depth_scale = 5000.0;  // raw depth units per metre
};

// The depth_scale range ReadCalibration accepts.
inline constexpr double kMinDepthScale = 1.0;
inline constexpr double kMaxDepthScale = 100000.0;

inline constexpr const char* kCalibrationFileName = "calibration.json";

// Reads calibration.json; throws InputError naming the file and the problem.
TumCalibration ReadCalibration(const std::string& path);
void WriteCalibration(const std::string& path, const TumCalibration& calibration);

// Published TUM RGB-D intrinsics (ROS default / calibrated values) chosen by
// the folder name: "freiburg1" -> fx 517.3 fy 516.5 cx 318.6 cy 255.3,
// "freiburg2" -> 520.9 521.0 325.1 249.7, "freiburg3" -> 535.4 539.2 320.1
// 247.6, otherwise the Kinect default 525 525 319.5 239.5; 640x480, scale 5000.
TumCalibration DefaultTumCalibration(const std::string& folder_name);

}  // namespace duskmap
