#include "slam/features/feature_extractor.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include <opencv2/imgproc.hpp>

#include "slam/core/check.h"

namespace duskmap {
namespace {

void AttachPoints(const cv::Mat& depth_m, const PinholeCamera* camera, double max_depth_m,
                  FrameFeatures* features) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  features->points_in_camera.assign(features->size(), Eigen::Vector3f(nan, nan, nan));
  if (depth_m.empty()) return;
  for (size_t i = 0; i < features->size(); ++i) {
    const cv::Point2f& pt = features->keypoints[i].pt;
    const int u = static_cast<int>(std::lround(pt.x));
    const int v = static_cast<int>(std::lround(pt.y));
    if (u < 0 || v < 0 || u >= depth_m.cols || v >= depth_m.rows) continue;
    const float z = depth_m.at<float>(v, u);
    if (!std::isfinite(z) || z <= 0.0f) continue;
    if (max_depth_m > 0.0 && z > max_depth_m) continue;
    features->points_in_camera[i] = camera->Unproject(pt.x, pt.y, z).cast<float>();
  }
}

}  // namespace

FeatureExtractor::FeatureExtractor(int max_features, double max_depth_m)
    : max_features_(max_features), max_depth_m_(max_depth_m) {
  SLAM_THROW_IF_NOT(ConfigError, max_features >= 1)
      << "features.max_features: must be >= 1, got " << max_features;
}

namespace {

void CheckImage8(const cv::Mat& image) {
  SLAM_THROW_IF_NOT(InputError, image.depth() == CV_8U)
      << "feature extraction: image must be 8-bit, got depth code " << image.depth()
      << " (convert 16-bit or float images to 8-bit first)";
  SLAM_THROW_IF_NOT(InputError, image.channels() == 1 || image.channels() == 3 || image.channels() == 4)
      << "feature extraction: image must have 1, 3 or 4 channels, got " << image.channels();
}

}  // namespace

cv::Mat ToGray8(const cv::Mat& image) {
  CheckImage8(image);
  if (image.channels() == 1) return image;
  cv::Mat gray;
  cv::cvtColor(image, gray, image.channels() == 3 ? cv::COLOR_BGR2GRAY : cv::COLOR_BGRA2GRAY);
  return gray;
}

cv::Mat ToBgr8(const cv::Mat& image) {
  CheckImage8(image);
  if (image.channels() == 3) return image;
  cv::Mat bgr;
  cv::cvtColor(image, bgr, image.channels() == 1 ? cv::COLOR_GRAY2BGR : cv::COLOR_BGRA2BGR);
  return bgr;
}

namespace {

// Depth, when given, must be CV_32F metres of the image's size with a valid camera.
void CheckDepth(const cv::Mat& image, const cv::Mat& depth_m, const PinholeCamera* camera) {
  if (!depth_m.empty()) {
    SLAM_THROW_IF_NOT(InputError, depth_m.type() == CV_32FC1)
        << "feature extraction: depth must be CV_32FC1 metres, got type code " << depth_m.type();
    SLAM_THROW_IF_NOT(InputError, depth_m.size() == image.size())
        << "feature extraction: depth is " << depth_m.cols << "x" << depth_m.rows
        << " but the image is " << image.cols << "x" << image.rows;
    SLAM_THROW_IF_NOT(InputError, camera != nullptr && camera->IsValid() &&
                                      camera->width == image.cols && camera->height == image.rows)
        << "feature extraction: depth given without a valid camera of the image's size";
  }
}

}  // namespace

FrameFeatures FeatureExtractor::Extract(const cv::Mat& image, const cv::Mat& depth_m,
                                        const PinholeCamera* camera) const {
  FrameFeatures features;
  features.kind = kind();
  CheckDepth(image, depth_m, camera);
  if (image.empty()) return features;
  SLAM_THROW_IF_NOT(InputError, DetectsOnImages())
      << "features.type " << name()
      << ": its features are read per dataset frame (session and image name), not from an image";
  const cv::Mat input = DetectsOnColor() ? ToBgr8(image) : ToGray8(image);
  DetectAndDescribe(input, &features.keypoints, &features.descriptors);
  Finish(depth_m, camera, &features);
  return features;
}

FrameFeatures FeatureExtractor::ExtractFrame(const RgbdFrame& frame) const {
  if (DetectsOnImages()) return Extract(frame.bgr, frame.depth_m, &frame.camera);
  FrameFeatures features;
  features.kind = kind();
  CheckDepth(frame.bgr, frame.depth_m, &frame.camera);
  ImportFrame(frame, &features.keypoints, &features.descriptors);
  Finish(frame.depth_m, &frame.camera, &features);
  return features;
}

void FeatureExtractor::ImportFrame(const RgbdFrame&, std::vector<cv::KeyPoint>*, cv::Mat*) const {
  SLAM_CHECK_MSG(false, "a type that detects on images imports nothing");
}

void FeatureExtractor::Finish(const cv::Mat& depth_m, const PinholeCamera* camera,
                              FrameFeatures* features) const {
  if (features->keypoints.empty()) {
    features->descriptors.release();
  } else {
    SLAM_CHECK(features->descriptors.rows == static_cast<int>(features->keypoints.size()));
    KeepStrongest(max_features_, &features->keypoints, &features->descriptors);
  }
  AttachPoints(depth_m, camera, max_depth_m_, features);
}

void KeepStrongest(int max_count, std::vector<cv::KeyPoint>* keypoints, cv::Mat* descriptors) {
  const size_t n = keypoints->size();
  SLAM_CHECK(descriptors->empty() || descriptors->rows == static_cast<int>(n));
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return std::abs((*keypoints)[a].response) > std::abs((*keypoints)[b].response);
  });
  const size_t kept = std::min(n, static_cast<size_t>(std::max(max_count, 0)));
  bool identity = kept == n;
  for (size_t i = 0; i < kept && identity; ++i) identity = order[i] == static_cast<int>(i);
  if (identity) return;
  std::vector<cv::KeyPoint> sorted(kept);
  cv::Mat sorted_descriptors;
  if (!descriptors->empty()) {
    sorted_descriptors.create(static_cast<int>(kept), descriptors->cols, descriptors->type());
  }
  for (size_t i = 0; i < kept; ++i) {
    sorted[i] = (*keypoints)[order[i]];
    if (!descriptors->empty()) descriptors->row(order[i]).copyTo(sorted_descriptors.row(i));
  }
  *keypoints = std::move(sorted);
  *descriptors = sorted_descriptors;
}

cv::Mat VocabularyDescriptors(const FrameFeatures& features, int vocabulary_features) {
  const int rows = std::min(features.descriptors.rows, std::max(vocabulary_features, 0));
  return features.descriptors.rowRange(0, rows);
}

}  // namespace duskmap
