#include "slam/features/h5_extractor.h"

#include <filesystem>
#include <system_error>

#include "slam/core/check.h"

namespace duskmap {
namespace fs = std::filesystem;

H5FeatureExtractor::H5FeatureExtractor(const H5FeatureOptions& options, int max_features,
                                       double max_depth_m)
    : FeatureExtractor(max_features, max_depth_m),
      options_(options),
      kind_(options.descriptor_kind == "binary" ? DescriptorKind::kBinary : DescriptorKind::kFloat),
      origin_(ParseKeypointOrigin(options.keypoint_origin, "features.h5.keypoint_origin")) {
  options_.Check();
  SLAM_THROW_IF_NOT(ConfigError, !options_.path.empty())
      << "features.h5.path: features of type h5 need the .h5 file (or folder of <session>.h5)";
  std::error_code error;
  per_session_files_ = fs::is_directory(options_.path, error);
  if (!per_session_files_) {  // H5FeatureFile names a missing, unreadable or foreign file
    files_[""] = std::make_unique<H5FeatureFile>(options_.path, H5FeatureFile::Mode::kRead);
  }
}

std::string H5FeatureExtractor::GroupOf(const RgbdFrame& frame) const {
  return per_session_files_ ? frame.image_name : frame.session + "/" + frame.image_name;
}

void H5FeatureExtractor::DetectAndDescribe(const cv::Mat&, std::vector<cv::KeyPoint>*,
                                           cv::Mat*) const {
  SLAM_CHECK_MSG(false, "Extract refuses an image for the h5 type before detection");
}

const H5FeatureFile& H5FeatureExtractor::FileFor(const std::string& session) const {
  std::lock_guard<std::mutex> lock(mutex_);
  const std::string key = per_session_files_ ? session : "";
  auto it = files_.find(key);
  if (it == files_.end()) {
    const std::string path = (fs::path(options_.path) / (session + ".h5")).string();
    it = files_.emplace(key, std::make_unique<H5FeatureFile>(path, H5FeatureFile::Mode::kRead)).first;
  }
  return *it->second;
}

void H5FeatureExtractor::ImportFrame(const RgbdFrame& frame, std::vector<cv::KeyPoint>* keypoints,
                                     cv::Mat* descriptors) const {
  SLAM_THROW_IF_NOT(InputError, !frame.image_name.empty() && !frame.session.empty())
      << options_.path << ": frame " << frame.frame_index << " of session '" << frame.session
      << "' has no image name to look up (RTAB-Map databases hold their images as blobs: "
         "import features for the image release instead)";
  const H5FeatureFile& file = FileFor(frame.session);
  const std::string group = GroupOf(frame);
  H5ImageFeatures features = file.Read(group, kind_, origin_);
  const float width = static_cast<float>(frame.bgr.empty() ? frame.camera.width : frame.bgr.cols);
  const float height = static_cast<float>(frame.bgr.empty() ? frame.camera.height : frame.bgr.rows);
  for (size_t i = 0; i < features.keypoints.size(); ++i) {
    const cv::Point2f& pt = features.keypoints[i].pt;
    SLAM_THROW_IF_NOT(InputError, pt.x >= 0.0f && pt.y >= 0.0f && pt.x < width && pt.y < height)
        << file.path() << ": " << group << "/keypoints: keypoint " << i << " at (" << pt.x << ", "
        << pt.y << ") is outside the " << width << "x" << height << " image ("
        << KeypointOriginName(origin_) << " convention)";
  }
  *keypoints = std::move(features.keypoints);
  *descriptors = features.descriptors;
}

}  // namespace duskmap
