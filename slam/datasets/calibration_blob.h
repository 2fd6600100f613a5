// Binary blobs of RTAB-Map databases (schema >= 0.18.0), all little-endian:
//  - transforms: 12 float32, row-major 3x4 [R | t]; all zeros = null;
//  - `Data.calibration`: one serialized camera model per camera,
//    int32[11] {ver_major, ver_minor, ver_patch, type, width, height, nK, nD,
//    nR, nP, nL}, then double K[nK], D[nD], R[nR], P[nP], float L[nL].
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include "slam/core/rigid3.h"
#include "slam/datasets/camera_calibration.h"

namespace duskmap {

inline constexpr size_t kTransformBlobBytes = 48;

// nullopt for the null transform (all zeros). Throws InputError "<where>: ..."
// for a blob that is not 48 bytes, non-finite values or a non-rotation.
std::optional<Rigid3d> ParseTransformBlob(const uint8_t* data, size_t size,
                                          const std::string& where);

// One mono camera model. Throws InputError naming `where` for a truncated or
// malformed blob, a stereo model or several cameras (not supported).
CameraCalibration ParseCalibrationBlob(const uint8_t* data, size_t size,
                                       const std::string& where);

}  // namespace duskmap
