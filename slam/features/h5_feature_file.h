// Local features of images in hloc's HDF5 layout, the file every learned-
// feature pipeline of the field writes (hloc's extract_features.py, and the
// COLMAP and kornia tooling around it): one group per image, named by the
// image's path ("1/rgb/60360.000000.png"; each '/' is a nested group), with
//   keypoints    N x 2 float (x, y in pixels)
//   descriptors  D x N float32 or float16 (compared by L2), or uint8 (binary:
//                D bytes, compared by Hamming)
//   scores       N float, optional: the keypoints' strength
// duskmap writes, and reads when present, the OpenCV keypoint fields hloc has
// no place for, so that its own features come back exactly (hloc ignores
// them):
//   keypoint_sizes N float32, keypoint_angles N float32, keypoint_octaves N int32
//
// Keypoint coordinates: OpenCV's and hloc's convention puts the centre of the
// top-left pixel at (0, 0); COLMAP's puts its top-left corner there (x + 0.5).
//
// The HDF5 library (Debian's serial build) is not thread-safe: every call of
// this file goes through one process-wide lock, so that extract jobs running
// in parallel may each hold a file open.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "slam/features/frame_features.h"

namespace duskmap {

enum class KeypointOrigin {
  kPixelCentre,  // OpenCV, hloc: the top-left pixel's centre is (0, 0)
  kPixelCorner,  // COLMAP: the top-left pixel's corner is (0, 0)
};

// "pixel_centre" / "pixel_corner"; Parse throws ConfigError naming `field`.
const char* KeypointOriginName(KeypointOrigin origin);
KeypointOrigin ParseKeypointOrigin(const std::string& name, const std::string& field);

// One image's features as stored, in file order, converted to OpenCV's
// convention. Without `scores` every response is 0; without duskmap's extra
// fields size is 0, angle -1 and octave 0 (cv::KeyPoint's defaults).
struct H5ImageFeatures {
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;  // N x D: CV_32F (float kinds) or CV_8U (binary)
  bool has_scores = false;
};

class H5FeatureFile {
 public:
  enum class Mode {
    kRead,    // an existing file, read only
    kCreate,  // a new file (an existing one is replaced)
  };
  // Throws InputError "<path>: <problem>" when the file is missing, is not
  // HDF5 or cannot be opened (truncated, damaged), or cannot be created.
  H5FeatureFile(const std::string& path, Mode mode);
  ~H5FeatureFile();
  H5FeatureFile(const H5FeatureFile&) = delete;
  H5FeatureFile& operator=(const H5FeatureFile&) = delete;

  const std::string& path() const { return path_; }

  // Whether the file holds a group named `image` (nested groups followed).
  bool HasImage(const std::string& image) const;

  // Reads the group `image`. Throws InputError "<path>: <image>: <problem>"
  // for a missing group, a missing or misshapen dataset, N that differs
  // between keypoints, descriptors and scores, descriptors whose dtype is not
  // `kind`'s (float32 or float16 for kFloat, uint8 for kBinary), NaN or
  // infinity in any value, a dataset that declares more values than the file
  // could hold (checked before allocating), or a dataset that cannot be read
  // (truncated file).
  H5ImageFeatures Read(const std::string& image, DescriptorKind kind,
                       KeypointOrigin origin = KeypointOrigin::kPixelCentre) const;

  // Writes the group `image` (creating its parent groups) with keypoints,
  // descriptors (D x N: float32 for kFloat, uint8 for kBinary, also when
  // there are none), scores (the responses) and duskmap's keypoint fields.
  // Throws InputError on a write failure or an existing group.
  void Write(const std::string& image, const std::vector<cv::KeyPoint>& keypoints,
             const cv::Mat& descriptors, DescriptorKind kind);

  // A text attribute of the file's root group (duskmap marks its exports
  // with "duskmap_feature_type"); nullopt when absent or not text.
  void WriteAttribute(const std::string& key, const std::string& value);
  std::optional<std::string> ReadAttribute(const std::string& key) const;

  // Flushes and closes; throws InputError if that fails (a full disk). The
  // destructor closes without reporting.
  void Close();

 private:
  std::string path_;
  int64_t file_ = -1;  // hid_t
};

}  // namespace duskmap
