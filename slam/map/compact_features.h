// The features of a map node as the map keeps them in memory and in the
// store: the compact counterpart of FrameFeatures (docs/engine.md, "Compact
// node features").
//  - Descriptors: binary rows are kept exactly; float rows are kept either
//    exactly (kFloat32) or quantized to 8 bits per element with a per-row
//    offset and step (kUint8, features/descriptor_quantization.h).
//  - Keypoints: 12 bytes instead of cv::KeyPoint's 28: x, y and size in
//    1/8 px (0 to 8191.875 px), angle in 1/90 degree (-1 = none) and
//    response (float; SuperGlue's keypoint scores). Octave and class_id have
//    no consumer after extraction and are not kept (decoded as 0 and -1).
//  - 3D points: three half floats (NaN kept; relative error <= 2^-11).
// Registration and the vocabulary use Decode(), which returns FrameFeatures.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

#include "slam/features/descriptor_quantization.h"
#include "slam/features/frame_features.h"

namespace duskmap {

struct PackedKeypoint {
  uint16_t x_eighth_px = 0;
  uint16_t y_eighth_px = 0;
  uint16_t size_eighth_px = 0;
  int16_t angle_ninetieth_deg = -90;  // -1 degree: no orientation
  float response = 0.0f;
};
static_assert(sizeof(PackedKeypoint) == 12, "PackedKeypoint is stored as 12 bytes");

class CompactFeatures {
 public:
  CompactFeatures() = default;

  // Throws InputError for inconsistent features (rows, points, types) or a
  // keypoint outside the packed range.
  static CompactFeatures Encode(const FrameFeatures& features, DescriptorStorage storage);
  // From stored parts (the map store); checks sizes and throws InputError.
  static CompactFeatures FromParts(DescriptorKind kind, DescriptorStorage storage,
                                   int descriptor_cv_type, cv::Mat codes,
                                   std::vector<float> row_offsets, std::vector<float> row_steps,
                                   std::vector<PackedKeypoint> keypoints,
                                   std::vector<uint16_t> half_points);

  FrameFeatures Decode() const;

  size_t size() const { return keypoints_.size(); }
  bool empty() const { return keypoints_.empty(); }
  DescriptorKind kind() const { return kind_; }
  DescriptorStorage storage() const { return storage_; }
  // OpenCV type and width of a decoded descriptor row (-1 / 0 when empty).
  int descriptor_cv_type() const { return descriptor_cv_type_; }
  int descriptor_cols() const { return codes_.cols; }
  // Bytes of one descriptor as extracted (decoded), e.g. 256 for SURF.
  size_t DescriptorBytes() const;
  bool HasPoint(size_t i) const;

  // Stored parts.
  const cv::Mat& codes() const { return codes_; }  // CV_8U rows, or CV_32F with kFloat32
  const std::vector<float>& row_offsets() const { return row_offsets_; }  // kUint8 float only
  const std::vector<float>& row_steps() const { return row_steps_; }
  const std::vector<PackedKeypoint>& keypoints() const { return keypoints_; }
  const std::vector<uint16_t>& half_points() const { return half_points_; }  // x y z per feature

  // Bytes held: descriptor codes and row scales; keypoints and 3D points.
  size_t DescriptorMemoryBytes() const;
  size_t KeypointPointMemoryBytes() const;

 private:
  DescriptorKind kind_ = DescriptorKind::kFloat;
  DescriptorStorage storage_ = DescriptorStorage::kFloat32;
  int descriptor_cv_type_ = -1;
  cv::Mat codes_;
  std::vector<float> row_offsets_;
  std::vector<float> row_steps_;
  std::vector<PackedKeypoint> keypoints_;
  std::vector<uint16_t> half_points_;
};

}  // namespace duskmap
