// The per-image calibration YAML written by RTAB-Map (`CameraModel::save`,
// OpenCV FileStorage syntax: `%YAML:1.0`, `---`, then `camera_name`,
// `image_width`, `image_height`, `camera_matrix`, optional
// `distortion_coefficients` / `distortion_model` / `rectification_matrix` /
// `projection_matrix`, and `local_transform`; matrices are {rows, cols, data}
// maps). Only this subset of YAML is parsed; unknown top-level keys are ignored.
#pragma once

#include <string>

#include "slam/datasets/camera_calibration.h"

namespace duskmap {

// Parses YAML text; `where` names the file in errors. Throws InputError
// "<where>:<line>: <problem>" on malformed content or a missing required key
// (camera_matrix, local_transform, image_width, image_height).
CameraCalibration ParseCalibrationYaml(const std::string& text, const std::string& where);

// Reads and parses a calibration file.
CameraCalibration ReadCalibrationYaml(const std::string& path);

}  // namespace duskmap
