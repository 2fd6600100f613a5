// The features of a map node as the map keeps them in memory and in the
// store: the compact counterpart of FrameFeatures (docs/engine.md, "Compact
// node features").
//  - Descriptors: binary rows are kept exactly; float rows are kept either
//    exactly (kFloat32) or quantized to 8 bits per element with a per-row
//    offset and step (kUint8, features/descriptor_quantization.h).
//  - Keypoints: 8 bytes instead of cv::KeyPoint's 28: x, y and size in
//    1/8 px (0 to 8191.875 px) and angle in 1/90 degree (-1 = none); the
//    response (a float, SuperGlue's keypoint score) apart, so that a map
//    loaded for a matcher that does not read it can drop it
//    (DropKeypointResponses). Octave and class_id have no consumer after
//    extraction and are not kept (decoded as 0 and -1).
//  - 3D points: three half floats (NaN kept; relative error <= 2^-11).
//  - Shared rows (localization only, map/shared_rows.h): a descriptor row
//    that is byte for byte a word's stored row (the row that created the
//    word) can be replaced by the word's id; Decode() then reads it from
//    the vocabulary. Such features are not saved.
// Registration and the vocabulary use Decode(), which returns FrameFeatures.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

#include "slam/features/descriptor_quantization.h"
#include "slam/features/frame_features.h"
#include "slam/vocabulary/word_row_source.h"
#include "slam/vocabulary/word_types.h"

namespace duskmap {

struct PackedKeypoint {
  uint16_t x_eighth_px = 0;
  uint16_t y_eighth_px = 0;
  uint16_t size_eighth_px = 0;
  int16_t angle_ninetieth_deg = -90;  // -1 degree: no orientation
};
static_assert(sizeof(PackedKeypoint) == 8, "PackedKeypoint is held as 8 bytes");

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
                                   std::vector<float> responses,
                                   std::vector<uint16_t> half_points);

  // `words` must hold the shared rows' words when there are any (throws
  // InputError naming the word otherwise).
  FrameFeatures Decode(const WordRowSource* words = nullptr) const;

  size_t size() const { return keypoints_.size(); }
  bool empty() const { return keypoints_.empty(); }
  DescriptorKind kind() const { return kind_; }
  DescriptorStorage storage() const { return storage_; }
  // OpenCV type and width of a decoded descriptor row (-1 / 0 when empty).
  int descriptor_cv_type() const { return descriptor_cv_type_; }
  int descriptor_cols() const { return descriptor_cols_; }
  // Bytes of one descriptor as extracted (decoded), e.g. 256 for SURF.
  size_t DescriptorBytes() const;
  bool HasPoint(size_t i) const;

  // Descriptor row i in the stored form of a `format` word (WordRowBytes
  // bytes), for features without shared rows. False when no word of that
  // format can hold the row exactly (float32 rows against 8-bit words and
  // the reverse).
  bool RowAsStoredWord(size_t i, WordRowFormat format, uint8_t* stored) const;
  // Replaces descriptor row i by a reference to row_words[i] wherever that
  // is not kNoWord (row_words: one entry per feature). The features must
  // have no shared row yet; throws InputError when a word is missing from
  // `words` or its stored row is not exactly row i.
  void ShareRowsWithWords(const std::vector<WordId>& row_words, const WordRowSource& words);
  bool has_shared_rows() const { return !shared_words_.empty(); }
  size_t num_shared_rows() const { return shared_words_.size(); }
  // Forgets the keypoint responses (decoded as 0 from then on): for a map
  // loaded for localization with a matcher that does not read them (every
  // matcher but SuperGlue). Such features are not saved.
  void DropKeypointResponses();
  bool has_responses() const { return responses_.size() == keypoints_.size(); }

  // Stored parts (the features' own rows: all of them unless rows are shared).
  const cv::Mat& codes() const { return codes_; }  // CV_8U rows, or CV_32F with kFloat32
  const std::vector<float>& row_offsets() const { return row_offsets_; }  // kUint8 float only
  const std::vector<float>& row_steps() const { return row_steps_; }
  const std::vector<PackedKeypoint>& keypoints() const { return keypoints_; }
  const std::vector<float>& responses() const { return responses_; }  // empty once dropped
  const std::vector<uint16_t>& half_points() const { return half_points_; }  // x y z per feature

  // Bytes held: descriptor codes, row scales and shared-row references;
  // keypoints (responses included while kept) and 3D points.
  size_t DescriptorMemoryBytes() const;
  size_t KeypointPointMemoryBytes() const;

 private:
  bool Quantized() const;  // float rows kept as 8-bit codes
  bool IsShared(size_t i) const;
  // Own row r (the r-th row not shared) as extracted (decoded).
  void DecodeOwnRow(int r, uint8_t* out) const;

  DescriptorKind kind_ = DescriptorKind::kFloat;
  DescriptorStorage storage_ = DescriptorStorage::kFloat32;
  int descriptor_cv_type_ = -1;
  int descriptor_cols_ = 0;
  cv::Mat codes_;
  std::vector<float> row_offsets_;
  std::vector<float> row_steps_;
  std::vector<PackedKeypoint> keypoints_;
  std::vector<float> responses_;  // parallel to keypoints_; empty once dropped
  std::vector<uint16_t> half_points_;
  std::vector<uint64_t> shared_mask_;  // bit i: row i is shared (empty when none is)
  std::vector<WordId> shared_words_;   // the shared rows' words, in feature order
};

}  // namespace duskmap
