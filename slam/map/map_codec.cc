#include "slam/map/map_codec.h"

#include <algorithm>
#include <cstring>
#include <limits>

#include "slam/core/check.h"

namespace duskmap {
namespace {

template <typename T>
Blob EncodeArray(const T* values, size_t count) {
  Blob blob(count * sizeof(T));
  if (count) std::memcpy(blob.data(), values, blob.size());
  return blob;
}

template <typename T>
std::vector<T> DecodeArray(const Blob& blob, size_t element_bytes, const std::string& what) {
  SLAM_THROW_IF_NOT(InputError, blob.size() % element_bytes == 0)
      << what << ": blob of " << blob.size() << " bytes is not a multiple of " << element_bytes;
  std::vector<T> values(blob.size() / sizeof(T));
  if (!blob.empty()) std::memcpy(values.data(), blob.data(), blob.size());
  return values;
}

std::vector<double> DecodeDoubles(const Blob& blob, size_t count, const std::string& what) {
  SLAM_THROW_IF_NOT(InputError, blob.size() == count * sizeof(double))
      << what << ": expected " << count * sizeof(double) << " bytes, got " << blob.size();
  return DecodeArray<double>(blob, sizeof(double), what);
}

}  // namespace

Blob EncodePose(const Rigid3d& pose) {
  const double v[7] = {pose.translation.x(), pose.translation.y(), pose.translation.z(),
                       pose.rotation.x(),    pose.rotation.y(),    pose.rotation.z(),
                       pose.rotation.w()};
  return EncodeArray(v, 7);
}

Rigid3d DecodePose(const Blob& blob, const std::string& what) {
  const std::vector<double> v = DecodeDoubles(blob, 7, what);
  const Eigen::Quaterniond q(v[6], v[3], v[4], v[5]);
  SLAM_THROW_IF_NOT(InputError, std::abs(q.norm() - 1.0) < 1e-6 && q.coeffs().allFinite() &&
                                    Eigen::Vector3d(v[0], v[1], v[2]).allFinite())
      << what << ": not a valid pose";
  // Assigned as stored (no re-normalisation), so save -> load is bit-exact.
  Rigid3d pose;
  pose.rotation = q;
  pose.translation = Eigen::Vector3d(v[0], v[1], v[2]);
  return pose;
}

Blob EncodeCamera(const PinholeCamera& camera) {
  const double v[6] = {static_cast<double>(camera.width), static_cast<double>(camera.height),
                       camera.fx, camera.fy, camera.cx, camera.cy};
  return EncodeArray(v, 6);
}

PinholeCamera DecodeCamera(const Blob& blob, const std::string& what) {
  const std::vector<double> v = DecodeDoubles(blob, 6, what);
  PinholeCamera camera;
  camera.width = static_cast<int>(v[0]);
  camera.height = static_cast<int>(v[1]);
  camera.fx = v[2];
  camera.fy = v[3];
  camera.cx = v[4];
  camera.cy = v[5];
  return camera;
}

Blob EncodeInformation(const Information6d& information) {
  return EncodeArray(information.data(), 36);
}

Information6d DecodeInformation(const Blob& blob, const std::string& what) {
  const std::vector<double> v = DecodeDoubles(blob, 36, what);
  return Eigen::Map<const Information6d>(v.data());
}

Blob EncodeKeypoints(const std::vector<cv::KeyPoint>& keypoints) {
  Blob blob;
  blob.reserve(keypoints.size() * 28);
  for (const cv::KeyPoint& k : keypoints) {
    const float f[5] = {k.pt.x, k.pt.y, k.size, k.angle, k.response};
    const int32_t i[2] = {k.octave, k.class_id};
    const Blob a = EncodeArray(f, 5), b = EncodeArray(i, 2);
    blob.insert(blob.end(), a.begin(), a.end());
    blob.insert(blob.end(), b.begin(), b.end());
  }
  return blob;
}

std::vector<cv::KeyPoint> DecodeKeypoints(const Blob& blob, const std::string& what) {
  SLAM_THROW_IF_NOT(InputError, blob.size() % 28 == 0)
      << what << ": blob of " << blob.size() << " bytes is not a multiple of 28";
  std::vector<cv::KeyPoint> keypoints(blob.size() / 28);
  for (size_t n = 0; n < keypoints.size(); ++n) {
    float f[5];
    int32_t i[2];
    std::memcpy(f, blob.data() + 28 * n, sizeof(f));
    std::memcpy(i, blob.data() + 28 * n + sizeof(f), sizeof(i));
    keypoints[n] = cv::KeyPoint(f[0], f[1], f[2], f[3], f[4], i[0], i[1]);
  }
  return keypoints;
}

Blob EncodePoints(const std::vector<Eigen::Vector3f>& points) {
  Blob blob(points.size() * 12);
  for (size_t n = 0; n < points.size(); ++n) std::memcpy(blob.data() + 12 * n, points[n].data(), 12);
  return blob;
}

std::vector<Eigen::Vector3f> DecodePoints(const Blob& blob, const std::string& what) {
  SLAM_THROW_IF_NOT(InputError, blob.size() % 12 == 0)
      << what << ": blob of " << blob.size() << " bytes is not a multiple of 12";
  std::vector<Eigen::Vector3f> points(blob.size() / 12);
  for (size_t n = 0; n < points.size(); ++n) std::memcpy(points[n].data(), blob.data() + 12 * n, 12);
  return points;
}

Blob EncodePackedKeypoints(const std::vector<PackedKeypoint>& keypoints,
                           const std::vector<float>& responses) {
  SLAM_CHECK(responses.size() == keypoints.size());
  Blob blob(keypoints.size() * kPackedKeypointBytes);
  for (size_t n = 0; n < keypoints.size(); ++n) {
    const PackedKeypoint& k = keypoints[n];
    uint8_t* out = blob.data() + kPackedKeypointBytes * n;
    std::memcpy(out, &k.x_eighth_px, 2);
    std::memcpy(out + 2, &k.y_eighth_px, 2);
    std::memcpy(out + 4, &k.size_eighth_px, 2);
    std::memcpy(out + 6, &k.angle_ninetieth_deg, 2);
    std::memcpy(out + 8, &responses[n], 4);
  }
  return blob;
}

std::vector<PackedKeypoint> DecodePackedKeypoints(const Blob& blob, const std::string& what,
                                                  std::vector<float>* responses) {
  SLAM_THROW_IF_NOT(InputError, blob.size() % kPackedKeypointBytes == 0)
      << what << ": blob of " << blob.size() << " bytes is not a multiple of "
      << kPackedKeypointBytes;
  std::vector<PackedKeypoint> keypoints(blob.size() / kPackedKeypointBytes);
  responses->resize(keypoints.size());
  for (size_t n = 0; n < keypoints.size(); ++n) {
    PackedKeypoint& k = keypoints[n];
    const uint8_t* in = blob.data() + kPackedKeypointBytes * n;
    std::memcpy(&k.x_eighth_px, in, 2);
    std::memcpy(&k.y_eighth_px, in + 2, 2);
    std::memcpy(&k.size_eighth_px, in + 4, 2);
    std::memcpy(&k.angle_ninetieth_deg, in + 6, 2);
    std::memcpy(&(*responses)[n], in + 8, 4);
  }
  return keypoints;
}

Blob EncodeHalfs(const std::vector<uint16_t>& values) {
  return EncodeArray(values.data(), values.size());
}

std::vector<uint16_t> DecodeHalfs(const Blob& blob, const std::string& what) {
  return DecodeArray<uint16_t>(blob, sizeof(uint16_t), what);
}

Blob EncodeFloats(const std::vector<float>& values) {
  return EncodeArray(values.data(), values.size());
}

std::vector<float> DecodeFloats(const Blob& blob, const std::string& what) {
  return DecodeArray<float>(blob, sizeof(float), what);
}

Blob EncodeWordIds(const std::vector<WordId>& ids) { return EncodeArray(ids.data(), ids.size()); }

std::vector<WordId> DecodeWordIds(const Blob& blob, const std::string& what) {
  return DecodeArray<WordId>(blob, sizeof(WordId), what);
}

Blob EncodeInt32s(const std::vector<int32_t>& values) {
  return EncodeArray(values.data(), values.size());
}

std::vector<int32_t> DecodeInt32s(const Blob& blob, const std::string& what) {
  return DecodeArray<int32_t>(blob, sizeof(int32_t), what);
}

Blob EncodeMatrix(const cv::Mat& matrix) {
  if (matrix.empty()) return Blob();
  const cv::Mat continuous = matrix.isContinuous() ? matrix : matrix.clone();
  return EncodeArray(continuous.data, continuous.total() * continuous.elemSize());
}

cv::Mat DecodeMatrix(const Blob& blob, int rows, int cols, int cv_type, const std::string& what) {
  if (rows == 0) {
    SLAM_THROW_IF_NOT(InputError, blob.empty()) << what << ": data for an empty matrix";
    return cv::Mat();
  }
  SLAM_THROW_IF_NOT(InputError, cv_type >= 0 && cols > 0 && rows > 0) << what << ": no descriptor layout";
  // The size the layout declares, checked against the blob before anything
  // is allocated (a damaged column count must not allocate gigabytes).
  const unsigned __int128 expected = static_cast<unsigned __int128>(rows) *
                                     static_cast<unsigned>(cols) * CV_ELEM_SIZE(cv_type);
  SLAM_THROW_IF_NOT(InputError, expected == blob.size())
      << what << ": expected " << static_cast<unsigned long long>(std::min<unsigned __int128>(
                                      expected, std::numeric_limits<uint64_t>::max()))
      << " bytes for " << rows << "x" << cols << ", got " << blob.size();
  cv::Mat matrix(rows, cols, cv_type);
  std::memcpy(matrix.data, blob.data(), blob.size());
  return matrix;
}

}  // namespace duskmap
