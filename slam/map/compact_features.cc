#include "slam/map/compact_features.h"

#include <cmath>
#include <cstring>
#include <string>

#include "slam/core/check.h"

namespace duskmap {
namespace {

constexpr float kEighthsPerPx = 8.0f;
constexpr float kMaxPackedPx = 65535.0f / kEighthsPerPx;  // 8191.875
constexpr float kNinetiethsPerDeg = 90.0f;

uint16_t PackPx(float value, const char* what, size_t index) {
  SLAM_THROW_IF_NOT(InputError, std::isfinite(value) && value >= 0.0f && value <= kMaxPackedPx)
      << "CompactFeatures: keypoint " << index << " " << what << " " << value
      << " px is outside [0, " << kMaxPackedPx << "]";
  return static_cast<uint16_t>(std::lround(value * kEighthsPerPx));
}

uint16_t HalfBits(float value) { return cv::float16_t(value).bits(); }
float FromHalf(uint16_t bits) { return static_cast<float>(cv::float16_t::fromBits(bits)); }

}  // namespace

CompactFeatures CompactFeatures::Encode(const FrameFeatures& f, DescriptorStorage storage) {
  const size_t n = f.size();
  SLAM_THROW_IF_NOT(InputError, static_cast<size_t>(f.descriptors.rows) == n ||
                                    (n == 0 && f.descriptors.empty()))
      << "CompactFeatures: " << n << " keypoints but " << f.descriptors.rows << " descriptors";
  SLAM_THROW_IF_NOT(InputError, f.points_in_camera.size() == n)
      << "CompactFeatures: " << f.points_in_camera.size() << " 3D points for " << n
      << " keypoints";
  CompactFeatures c;
  c.kind_ = f.kind;
  c.storage_ = storage;
  if (!f.descriptors.empty()) {
    const int type = f.descriptors.type();
    SLAM_THROW_IF_NOT(InputError, (f.kind == DescriptorKind::kFloat && type == CV_32F) ||
                                      (f.kind == DescriptorKind::kBinary && type == CV_8U))
        << "CompactFeatures: descriptor type " << type << " does not match its kind";
    c.descriptor_cv_type_ = type;
    c.descriptor_cols_ = f.descriptors.cols;
    if (f.kind == DescriptorKind::kFloat && storage == DescriptorStorage::kUint8) {
      c.codes_.create(f.descriptors.rows, f.descriptors.cols, CV_8U);
      c.row_offsets_.resize(n);
      c.row_steps_.resize(n);
      for (int r = 0; r < f.descriptors.rows; ++r) {
        RowScale scale;
        SLAM_THROW_IF_NOT(InputError, QuantizeRow(f.descriptors.ptr<float>(r), f.descriptors.cols,
                                                  c.codes_.ptr<uint8_t>(r), &scale))
            << "CompactFeatures: descriptor " << r << " is not finite";
        c.row_offsets_[r] = scale.offset;
        c.row_steps_[r] = scale.step;
      }
    } else {
      c.codes_ = f.descriptors.clone();
    }
  }
  c.keypoints_.resize(n);
  c.responses_.resize(n);
  c.half_points_.resize(3 * n);
  for (size_t i = 0; i < n; ++i) {
    const cv::KeyPoint& k = f.keypoints[i];
    PackedKeypoint& p = c.keypoints_[i];
    p.x_eighth_px = PackPx(k.pt.x, "x", i);
    p.y_eighth_px = PackPx(k.pt.y, "y", i);
    p.size_eighth_px = PackPx(k.size, "size", i);
    float angle = k.angle;
    if (angle < 0.0f) {
      p.angle_ninetieth_deg = -90;
    } else {
      angle = std::fmod(angle, 360.0f);
      p.angle_ninetieth_deg = static_cast<int16_t>(std::lround(angle * kNinetiethsPerDeg) % 32400);
    }
    c.responses_[i] = k.response;
    for (int a = 0; a < 3; ++a) c.half_points_[3 * i + a] = HalfBits(f.points_in_camera[i][a]);
  }
  return c;
}

CompactFeatures CompactFeatures::FromParts(DescriptorKind kind, DescriptorStorage storage,
                                           int descriptor_cv_type, cv::Mat codes,
                                           std::vector<float> row_offsets,
                                           std::vector<float> row_steps,
                                           std::vector<PackedKeypoint> keypoints,
                                           std::vector<float> responses,
                                           std::vector<uint16_t> half_points) {
  const size_t n = keypoints.size();
  SLAM_THROW_IF_NOT(InputError, responses.size() == n)
      << "CompactFeatures: " << responses.size() << " keypoint responses for " << n
      << " keypoints";
  SLAM_THROW_IF_NOT(InputError, half_points.size() == 3 * n)
      << "CompactFeatures: " << half_points.size() / 3 << " 3D points for " << n << " keypoints";
  SLAM_THROW_IF_NOT(InputError, static_cast<size_t>(codes.rows) == n || (n == 0 && codes.empty()))
      << "CompactFeatures: " << codes.rows << " descriptors for " << n << " keypoints";
  const bool quantized = kind == DescriptorKind::kFloat && storage == DescriptorStorage::kUint8;
  if (!codes.empty()) {
    const int expected_code_type = quantized || kind == DescriptorKind::kBinary ? CV_8U : CV_32F;
    SLAM_THROW_IF_NOT(InputError, codes.type() == expected_code_type &&
                                      descriptor_cv_type ==
                                          (kind == DescriptorKind::kBinary ? CV_8U : CV_32F))
        << "CompactFeatures: descriptor codes of type " << codes.type()
        << " do not match the descriptor kind and storage";
  }
  const size_t scales = quantized ? static_cast<size_t>(codes.rows) : 0;
  SLAM_THROW_IF_NOT(InputError, row_offsets.size() == scales && row_steps.size() == scales)
      << "CompactFeatures: " << row_offsets.size() << " row offsets and " << row_steps.size()
      << " row steps for " << scales << " quantized descriptors";
  CompactFeatures c;
  c.kind_ = kind;
  c.storage_ = storage;
  c.descriptor_cv_type_ = codes.empty() ? -1 : descriptor_cv_type;
  c.descriptor_cols_ = codes.empty() ? 0 : codes.cols;
  c.codes_ = std::move(codes);
  c.row_offsets_ = std::move(row_offsets);
  c.row_steps_ = std::move(row_steps);
  c.keypoints_ = std::move(keypoints);
  c.responses_ = std::move(responses);
  c.half_points_ = std::move(half_points);
  return c;
}

bool CompactFeatures::Quantized() const {
  return kind_ == DescriptorKind::kFloat && storage_ == DescriptorStorage::kUint8;
}

bool CompactFeatures::IsShared(size_t i) const {
  return !shared_mask_.empty() && ((shared_mask_[i / 64] >> (i % 64)) & 1u);
}

void CompactFeatures::DecodeOwnRow(int r, uint8_t* out) const {
  if (Quantized()) {
    DequantizeRow(codes_.ptr<uint8_t>(r), codes_.cols, {row_offsets_[r], row_steps_[r]},
                  reinterpret_cast<float*>(out));
  } else {
    std::memcpy(out, codes_.ptr(r), DescriptorBytes());
  }
}

FrameFeatures CompactFeatures::Decode(const WordRowSource* words) const {
  FrameFeatures f;
  f.kind = kind_;
  const size_t n = size();
  if (!has_shared_rows()) {
    if (!codes_.empty()) {
      if (Quantized()) {
        f.descriptors.create(codes_.rows, codes_.cols, CV_32F);
        for (int r = 0; r < codes_.rows; ++r) DecodeOwnRow(r, f.descriptors.ptr(r));
      } else {
        f.descriptors = codes_.clone();
      }
    }
  } else {
    SLAM_THROW_IF_NOT(InputError, words != nullptr)
        << "CompactFeatures: " << shared_words_.size()
        << " descriptor rows are shared with words, but no words were given";
    f.descriptors.create(static_cast<int>(n), descriptor_cols_, descriptor_cv_type_);
    int own = 0;
    size_t shared = 0;
    for (size_t i = 0; i < n; ++i) {
      uint8_t* out = f.descriptors.ptr(static_cast<int>(i));
      if (!IsShared(i)) {
        DecodeOwnRow(own++, out);
        continue;
      }
      const WordId word = shared_words_[shared++];
      const uint8_t* stored = words->FindStoredRow(word);
      SLAM_THROW_IF_NOT(InputError, stored != nullptr)
          << "CompactFeatures: descriptor row " << i << " is shared with word " << word
          << ", which the vocabulary does not hold";
      DecodeWordRow(words->stored_row_format(), stored, descriptor_cols_, out);
    }
  }
  f.keypoints.resize(n);
  f.points_in_camera.resize(n);
  const bool responses = has_responses();
  for (size_t i = 0; i < n; ++i) {
    const PackedKeypoint& p = keypoints_[i];
    const float angle =
        p.angle_ninetieth_deg < 0 ? -1.0f : p.angle_ninetieth_deg / kNinetiethsPerDeg;
    f.keypoints[i] = cv::KeyPoint(p.x_eighth_px / kEighthsPerPx, p.y_eighth_px / kEighthsPerPx,
                                  p.size_eighth_px / kEighthsPerPx, angle,
                                  responses ? responses_[i] : 0.0f, 0, -1);
    f.points_in_camera[i] = Eigen::Vector3f(FromHalf(half_points_[3 * i]),
                                            FromHalf(half_points_[3 * i + 1]),
                                            FromHalf(half_points_[3 * i + 2]));
  }
  return f;
}

size_t CompactFeatures::DescriptorBytes() const {
  return static_cast<size_t>(descriptor_cols_) * (descriptor_cv_type_ == CV_32F ? 4 : 1);
}

bool CompactFeatures::RowAsStoredWord(size_t i, WordRowFormat format, uint8_t* stored) const {
  SLAM_CHECK(!has_shared_rows() && i < size() && !codes_.empty());
  const int r = static_cast<int>(i);
  if (kind_ == DescriptorKind::kBinary) {
    if (format != WordRowFormat::kBinary) return false;
    std::memcpy(stored, codes_.ptr(r), DescriptorBytes());
  } else if (Quantized()) {
    if (format != WordRowFormat::kQuantized8) return false;
    StoreQuantizedWordRow(codes_.ptr(r), {row_offsets_[i], row_steps_[i]}, codes_.cols, stored);
  } else {
    if (format != WordRowFormat::kFloat32) return false;
    std::memcpy(stored, codes_.ptr(r), DescriptorBytes());
  }
  return true;
}

void CompactFeatures::ShareRowsWithWords(const std::vector<WordId>& row_words,
                                         const WordRowSource& words) {
  SLAM_CHECK(!has_shared_rows() && row_words.size() == size());
  const WordRowFormat format = words.stored_row_format();
  std::vector<uint8_t> mine(WordRowBytes(format, descriptor_cols_));
  std::vector<uint64_t> mask((size() + 63) / 64, 0);
  std::vector<WordId> shared;
  for (size_t i = 0; i < size(); ++i) {
    if (row_words[i] == kNoWord) continue;
    const uint8_t* stored = words.FindStoredRow(row_words[i]);
    SLAM_THROW_IF_NOT(InputError, stored != nullptr && RowAsStoredWord(i, format, mine.data()) &&
                                      std::memcmp(stored, mine.data(), mine.size()) == 0)
        << "CompactFeatures: descriptor row " << i << " is not the stored row of word "
        << row_words[i];
    mask[i / 64] |= uint64_t{1} << (i % 64);
    shared.push_back(row_words[i]);
  }
  if (shared.empty()) return;
  const int own_rows = static_cast<int>(size() - shared.size());
  cv::Mat codes;
  std::vector<float> offsets, steps;
  if (own_rows > 0) codes.create(own_rows, codes_.cols, codes_.type());
  int own = 0;
  const size_t row_bytes = codes_.cols * codes_.elemSize();
  for (size_t i = 0; i < size(); ++i) {
    if ((mask[i / 64] >> (i % 64)) & 1u) continue;
    std::memcpy(codes.ptr(own++), codes_.ptr(static_cast<int>(i)), row_bytes);
    if (Quantized()) {
      offsets.push_back(row_offsets_[i]);
      steps.push_back(row_steps_[i]);
    }
  }
  codes_ = codes;
  row_offsets_ = std::move(offsets);
  row_steps_ = std::move(steps);
  shared_mask_ = std::move(mask);
  shared_words_ = std::move(shared);
}

bool CompactFeatures::HasPoint(size_t i) const {
  for (int a = 0; a < 3; ++a) {
    if (!std::isfinite(FromHalf(half_points_[3 * i + a]))) return false;
  }
  return true;
}

size_t CompactFeatures::DescriptorMemoryBytes() const {
  return codes_.total() * codes_.elemSize() +
         (row_offsets_.size() + row_steps_.size()) * sizeof(float) +
         shared_mask_.size() * sizeof(uint64_t) + shared_words_.size() * sizeof(WordId);
}

void CompactFeatures::DropKeypointResponses() {
  std::vector<float>().swap(responses_);
}

size_t CompactFeatures::KeypointPointMemoryBytes() const {
  return keypoints_.size() * sizeof(PackedKeypoint) + responses_.size() * sizeof(float) +
         half_points_.size() * sizeof(uint16_t);
}

}  // namespace duskmap
