// The on-disk cache of one session's extracted features: every frame's
// metadata (index, time, camera, extrinsics, odometry, ground truth; no
// images) with its keypoints, descriptors and 3D points, so that map and
// localization jobs never decode an image or extract a feature again.
//
// Layout (little-endian host layout, one file per session and extractor):
//   "DUSKFC01", extractor, session name, clock time, ground-truth flag,
//   frame count, then per frame 'F' + metadata + features, then 'E'.
// Every variable-size field is a u64 length and its bytes; blobs use the map
// store's encodings (slam/map/map_codec.h).
#pragma once

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>

#include "slam/core/rgbd_frame.h"
#include "slam/engine/session_runs.h"
#include "slam/features/frame_features.h"

namespace duskmap {

class FeatureCacheWriter {
 public:
  // Creates `path` anew (an existing file is removed, not truncated: it may be
  // hard-linked from a shared cache); throws InputError when it cannot be written.
  FeatureCacheWriter(const std::filesystem::path& path, const std::string& extractor,
                     const SessionInfo& session);
  // Appends one frame (its images are not stored).
  void Append(const RgbdFrame& frame, const FrameFeatures& features);
  // Writes the end marker and the frame count; throws InputError on a write
  // error. The file is incomplete until Close() returned.
  void Close();
  int64_t num_frames() const { return num_frames_; }

 private:
  // InputError "<path>: write failed: <the system's reason>" once a write failed.
  void ThrowIfWriteFailed() const;

  std::filesystem::path path_;
  std::fstream out_;
  std::streampos count_position_;
  int64_t num_frames_ = 0;
  bool closed_ = false;
};

// Reads a cache file front to back as a FrameSource: frames without images,
// with their features. Throws InputError naming the file when it is missing,
// of another format, truncated or corrupt.
class FeatureCacheReader : public FrameSource {
 public:
  explicit FeatureCacheReader(const std::filesystem::path& path);
  const SessionInfo& info() const override { return info_; }
  const std::string& extractor() const { return extractor_; }
  std::optional<RgbdFrame> Next(std::optional<FrameFeatures>* features) override;

 private:
  std::filesystem::path path_;
  std::ifstream in_;
  std::string extractor_;
  SessionInfo info_;
  int64_t frames_read_ = 0;
  bool done_ = false;
};

}  // namespace duskmap
