// Features imported from files in hloc's HDF5 layout (h5_feature_file.h):
// feature type "h5". It detects nothing; for each dataset frame it reads the
// group named by the frame's session and image name, keeps the strongest
// max_features by score (file order without scores) and attaches 3D points
// from the frame's depth, as every other type does. Maps, localization, the
// experiment runner and the report use it like any built-in type.
#pragma once

#include <map>
#include <memory>
#include <mutex>
#include <string>

#include "slam/features/feature_extractor.h"
#include "slam/features/feature_registry.h"
#include "slam/features/h5_feature_file.h"

namespace duskmap {

class H5FeatureExtractor : public FeatureExtractor {
 public:
  // Opens options.path now when it is a file (a folder's per-session files
  // are opened on first use); throws InputError naming the path when it is
  // missing or not HDF5.
  H5FeatureExtractor(const H5FeatureOptions& options, int max_features, double max_depth_m);

  std::string name() const override { return FeatureTypeName(FeatureTypeId::kH5); }
  DescriptorKind kind() const override { return kind_; }
  bool DetectsOnImages() const override { return false; }

  // The group a frame's features are read from: "<session>/<image name>" in
  // a dataset file, "<image name>" in a folder's "<session>.h5".
  std::string GroupOf(const RgbdFrame& frame) const;

 protected:
  void DetectAndDescribe(const cv::Mat& gray, std::vector<cv::KeyPoint>* keypoints,
                         cv::Mat* descriptors) const override;
  // Throws InputError "<file>: <group>: <problem>" (h5_feature_file.h), also
  // for a keypoint outside the frame's image and a frame without an image name.
  void ImportFrame(const RgbdFrame& frame, std::vector<cv::KeyPoint>* keypoints,
                   cv::Mat* descriptors) const override;

 private:
  const H5FeatureFile& FileFor(const std::string& session) const;

  H5FeatureOptions options_;
  DescriptorKind kind_;
  KeypointOrigin origin_;
  bool per_session_files_ = false;
  mutable std::mutex mutex_;
  mutable std::map<std::string, std::unique_ptr<H5FeatureFile>> files_;  // by session ("" = dataset file)
};

}  // namespace duskmap
