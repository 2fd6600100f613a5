// Binary encodings of the map's per-row values as stored in SQLite blobs
// (little-endian host layout, fixed element sizes). Decoders check sizes and
// throw InputError naming `what` (e.g. "map.db: node 12 keypoints").
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "slam/core/camera.h"
#include "slam/core/graph_types.h"
#include "slam/core/rigid3.h"
#include "slam/map/compact_features.h"
#include "slam/vocabulary/word_types.h"

namespace duskmap {

using Blob = std::vector<uint8_t>;

Blob EncodePose(const Rigid3d& pose);  // tx ty tz qx qy qz qw (doubles)
Rigid3d DecodePose(const Blob& blob, const std::string& what);

Blob EncodeCamera(const PinholeCamera& camera);  // width height fx fy cx cy (doubles)
PinholeCamera DecodeCamera(const Blob& blob, const std::string& what);

Blob EncodeInformation(const Information6d& information);  // 36 doubles, column-major
Information6d DecodeInformation(const Blob& blob, const std::string& what);

// x y size angle response (float) octave class_id (int32): 28 bytes each.
Blob EncodeKeypoints(const std::vector<cv::KeyPoint>& keypoints);
std::vector<cv::KeyPoint> DecodeKeypoints(const Blob& blob, const std::string& what);

Blob EncodePoints(const std::vector<Eigen::Vector3f>& points);  // 3 floats each
std::vector<Eigen::Vector3f> DecodePoints(const Blob& blob, const std::string& what);

// Compact node features (compact_features.h): 12-byte packed keypoints
// (x y size angle as uint16/int16, then the response as float,
// little-endian), three half floats per 3D point, and float arrays (row
// offsets and steps).
inline constexpr size_t kPackedKeypointBytes = 12;
// `responses`: one per keypoint.
Blob EncodePackedKeypoints(const std::vector<PackedKeypoint>& keypoints,
                           const std::vector<float>& responses);
std::vector<PackedKeypoint> DecodePackedKeypoints(const Blob& blob, const std::string& what,
                                                  std::vector<float>* responses);
Blob EncodeHalfs(const std::vector<uint16_t>& values);
std::vector<uint16_t> DecodeHalfs(const Blob& blob, const std::string& what);
Blob EncodeFloats(const std::vector<float>& values);
std::vector<float> DecodeFloats(const Blob& blob, const std::string& what);

Blob EncodeWordIds(const std::vector<WordId>& ids);
std::vector<WordId> DecodeWordIds(const Blob& blob, const std::string& what);
Blob EncodeInt32s(const std::vector<int32_t>& values);
std::vector<int32_t> DecodeInt32s(const Blob& blob, const std::string& what);

// The raw rows of a continuous matrix; decoding needs rows, cols and type.
Blob EncodeMatrix(const cv::Mat& matrix);
cv::Mat DecodeMatrix(const Blob& blob, int rows, int cols, int cv_type, const std::string& what);

}  // namespace duskmap
