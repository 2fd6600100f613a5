// The FeatureExtractor interface: image (+ optional registered depth) in,
// FrameFeatures out — at most max_features keypoints, strongest response
// first, one descriptor row each, a 3D point per keypoint (NaN without depth).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "slam/core/camera.h"
#include "slam/core/rgbd_frame.h"
#include "slam/features/feature_options.h"
#include "slam/features/frame_features.h"

namespace duskmap {

class FeatureExtractor {
 public:
  explicit FeatureExtractor(int max_features, double max_depth_m = 0.0);
  virtual ~FeatureExtractor() = default;

  virtual std::string name() const = 0;
  virtual DescriptorKind kind() const = 0;
  int max_features() const { return max_features_; }

  // `image`: 8-bit gray, BGR or BGRA (other depths throw InputError). An empty
  // image, or one too small or too flat for the detector, gives no features.
  // `depth_m`: empty, or CV_32F metres of the image's size (0/NaN = no depth);
  // with depth, `camera` must be valid and of the image's size.
  FrameFeatures Extract(const cv::Mat& image, const cv::Mat& depth_m = cv::Mat(),
                        const PinholeCamera* camera = nullptr) const;

  // The features of a dataset frame: detected on its image (as Extract with
  // its depth and camera) or, for a type that imports them (h5), read for
  // the frame's session and image name; either way at most max_features,
  // strongest first, with 3D points from the frame's depth.
  FrameFeatures ExtractFrame(const RgbdFrame& frame) const;

  // False for the types whose features come from a file per image (h5):
  // they need ExtractFrame, and Extract on a bare image throws InputError.
  virtual bool DetectsOnImages() const { return true; }

  // True for the types that detect on colour (an ONNX model with RGB input):
  // DetectAndDescribe then gets the image as 8-bit BGR instead of gray.
  virtual bool DetectsOnColor() const { return false; }

 protected:
  // Types that import features override this (and DetectsOnImages): the
  // frame's keypoints and one descriptor row each, in any order.
  virtual void ImportFrame(const RgbdFrame& frame, std::vector<cv::KeyPoint>* keypoints,
                           cv::Mat* descriptors) const;

  // Detects and describes on an 8-bit non-empty image, single-channel (or
  // BGR when DetectsOnColor()). May
  // return more than max_features (Extract keeps the strongest) and in any
  // order; descriptors must have one row per keypoint (or be empty when there
  // are no keypoints).
  virtual void DetectAndDescribe(const cv::Mat& image, std::vector<cv::KeyPoint>* keypoints,
                                 cv::Mat* descriptors) const = 0;

 private:
  // Keeps the strongest max_features and attaches their 3D points.
  void Finish(const cv::Mat& depth_m, const PinholeCamera* camera, FrameFeatures* features) const;

  int max_features_;
  double max_depth_m_;
};

// Converts 8-bit gray/BGR/BGRA to 8-bit gray; throws InputError otherwise.
cv::Mat ToGray8(const cv::Mat& image);
// Converts 8-bit gray/BGR/BGRA to 8-bit BGR; throws InputError otherwise.
cv::Mat ToBgr8(const cv::Mat& image);

// Sorts keypoints by |response| descending (stable: ties keep input order),
// keeps at most `max_count` and reorders the descriptor rows to match.
void KeepStrongest(int max_count, std::vector<cv::KeyPoint>* keypoints, cv::Mat* descriptors);

// The descriptors quantized into the vocabulary: the first
// min(size, vocabulary_features) rows (Kp/MaxFeatures), a view, not a copy.
cv::Mat VocabularyDescriptors(const FrameFeatures& features, int vocabulary_features);

// CreateFeatureExtractor: feature_factory.h.

}  // namespace duskmap
