#include "slam/datasets/calibration_blob.h"

#include <cstring>
#include <vector>

#include "slam/core/check.h"

namespace duskmap {
namespace {

constexpr size_t kMonoHeaderInts = 11;
constexpr int kMonoType = 0;
constexpr int kStereoType = 1;

template <typename T>
T ReadAt(const uint8_t* data, size_t offset) {
  T value;
  std::memcpy(&value, data + offset, sizeof(T));
  return value;
}

std::vector<double> ReadDoubles(const uint8_t* data, size_t* offset, int count) {
  std::vector<double> values(count);
  for (int i = 0; i < count; ++i) values[i] = ReadAt<double>(data, *offset + 8 * i);
  *offset += 8 * static_cast<size_t>(count);
  return values;
}

// RTAB-Map stores the 6 equidistant coefficients as k1 k2 p1 p2 k3 k4.
void SetDistortion(const std::vector<double>& d, CameraCalibration* calibration,
                   const std::string& where) {
  const size_t n = d.size();
  SLAM_THROW_IF_NOT(InputError, n == 0 || n == 4 || n == 5 || n == 6 || n == 8 || n == 12 ||
                                    n == 14)
      << where << ": unsupported number of distortion coefficients " << n;
  if (n == 6) {
    calibration->fisheye = true;
    calibration->distortion = {d[0], d[1], d[4], d[5]};
  } else {
    calibration->distortion = d;
  }
}

}  // namespace

std::optional<Rigid3d> ParseTransformBlob(const uint8_t* data, size_t size,
                                          const std::string& where) {
  SLAM_THROW_IF_NOT(InputError, size == kTransformBlobBytes)
      << where << ": transform blob has " << size << " bytes, expected 48";
  double values[12];
  bool all_zero = true;
  for (int i = 0; i < 12; ++i) {
    values[i] = ReadAt<float>(data, 4 * i);
    all_zero = all_zero && values[i] == 0.0;
  }
  if (all_zero) return std::nullopt;
  return RigidFromRowMajor3x4(values, where);
}

CameraCalibration ParseCalibrationBlob(const uint8_t* data, size_t size,
                                       const std::string& where) {
  SLAM_THROW_IF_NOT(InputError, size >= 4 * kMonoHeaderInts)
      << where << ": calibration blob is truncated (" << size << " bytes)";
  int32_t header[kMonoHeaderInts];
  for (size_t i = 0; i < kMonoHeaderInts; ++i) header[i] = ReadAt<int32_t>(data, 4 * i);
  SLAM_THROW_IF_NOT(InputError, header[3] != kStereoType)
      << where << ": stereo calibration is not supported";
  SLAM_THROW_IF_NOT(InputError, header[3] == kMonoType)
      << where << ": unknown camera model type " << header[3];
  const int nk = header[6], nd = header[7], nr = header[8], np = header[9], nl = header[10];
  SLAM_THROW_IF_NOT(InputError, nk == 9 && nd >= 0 && nd <= 14 && (nr == 0 || nr == 9) &&
                                    (np == 0 || np == 12) && (nl == 0 || nl == 12))
      << where << ": calibration blob has invalid element counts K=" << nk << " D=" << nd
      << " R=" << nr << " P=" << np << " L=" << nl;
  const size_t record_bytes = 4 * kMonoHeaderInts + 8 * size_t(nk + nd + nr + np) + 4 * size_t(nl);
  SLAM_THROW_IF_NOT(InputError, size >= record_bytes)
      << where << ": calibration blob is truncated (" << size << " of " << record_bytes
      << " bytes)";
  SLAM_THROW_IF_NOT(InputError, size == record_bytes)
      << where << ": calibration holds several cameras (" << size << " bytes for a "
      << record_bytes << "-byte record); multi-camera rigs are not supported";
  CameraCalibration calibration;
  calibration.image_width = header[4];
  calibration.image_height = header[5];
  size_t offset = 4 * kMonoHeaderInts;
  const std::vector<double> k = ReadDoubles(data, &offset, nk);
  calibration.camera_matrix = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(k.data());
  SetDistortion(ReadDoubles(data, &offset, nd), &calibration, where);
  if (nr == 9) {
    const std::vector<double> r = ReadDoubles(data, &offset, nr);
    calibration.rectification = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(r.data());
  }
  if (np == 12) {
    const std::vector<double> p = ReadDoubles(data, &offset, np);
    calibration.projection = Eigen::Map<const Eigen::Matrix<double, 3, 4, Eigen::RowMajor>>(p.data());
  }
  if (nl == 12) {
    const std::optional<Rigid3d> local =
        ParseTransformBlob(data + offset, 4 * static_cast<size_t>(nl), where + " local_transform");
    if (local) calibration.body_from_camera = *local;
  }
  CheckCalibration(calibration, where);
  return calibration;
}

}  // namespace duskmap
