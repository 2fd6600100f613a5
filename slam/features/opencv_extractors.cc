#include "slam/features/opencv_extractors.h"

#include <algorithm>
#include <cmath>

#include "slam/core/check.h"
#include "slam/features/feature_registry.h"

namespace duskmap {

OpenCvExtractor::OpenCvExtractor(std::string name, cv::Ptr<cv::Feature2D> feature,
                                 DescriptorKind kind, int max_features, double max_depth_m,
                                 bool root_sift, OpenCvPasses passes)
    : FeatureExtractor(max_features, max_depth_m),
      name_(std::move(name)),
      feature_(std::move(feature)),
      kind_(kind),
      root_sift_(root_sift),
      passes_(passes) {}

void OpenCvExtractor::DetectAndDescribe(const cv::Mat& gray, std::vector<cv::KeyPoint>* keypoints,
                                        cv::Mat* descriptors) const {
  // OpenCV's pyramids assert on images that vanish at their coarsest level.
  if (std::min(gray.cols, gray.rows) < kMinImageSidePx) return;
  if (passes_ == OpenCvPasses::kSinglePass) {
    // Every keypoint described; FeatureExtractor::Finish keeps the strongest.
    feature_->detectAndCompute(gray, cv::noArray(), *keypoints, *descriptors);
  } else {
    // Limit before describing (the reference's limitKeypoints), strongest first.
    *keypoints = DetectStrongest(*feature_, gray, max_features());
    if (keypoints->empty()) return;
    feature_->compute(gray, *keypoints, *descriptors);
  }
  if (keypoints->empty()) {
    descriptors->release();
    return;
  }
  SLAM_CHECK(descriptors->rows == static_cast<int>(keypoints->size()));
  if (root_sift_ && descriptors->type() == CV_32F) {
    for (int r = 0; r < descriptors->rows; ++r) {
      float* row = descriptors->ptr<float>(r);
      double l1 = 0.0;
      for (int c = 0; c < descriptors->cols; ++c) l1 += std::abs(row[c]);
      if (l1 <= 0.0) continue;
      for (int c = 0; c < descriptors->cols; ++c) {
        row[c] = static_cast<float>(std::sqrt(std::abs(row[c]) / l1));
      }
    }
  }
}

std::vector<cv::KeyPoint> DetectStrongest(cv::Feature2D& feature, const cv::Mat& gray,
                                          int max_features) {
  std::vector<cv::KeyPoint> keypoints;
  if (std::min(gray.cols, gray.rows) < OpenCvExtractor::kMinImageSidePx) return keypoints;
  feature.detect(gray, keypoints);
  cv::Mat none;
  KeepStrongest(max_features, &keypoints, &none);
  return keypoints;
}

cv::Ptr<cv::Feature2D> CreateSiftFeature2D(const SiftOptions& o, int max_features) {
  o.Check();
  return cv::SIFT::create(max_features, o.octave_layers, o.contrast_threshold, o.edge_threshold,
                          o.sigma);
}

std::unique_ptr<FeatureExtractor> CreateSiftExtractor(const SiftOptions& o, int max_features,
                                                      double max_depth_m) {
  return std::make_unique<OpenCvExtractor>(FeatureTypeName(FeatureTypeId::kSift),
                                           CreateSiftFeature2D(o, max_features),
                                           DescriptorKind::kFloat, max_features, max_depth_m,
                                           o.root_sift);
}

std::unique_ptr<FeatureExtractor> CreateOrbExtractor(const OrbOptions& o, int max_features,
                                                     double max_depth_m) {
  o.Check();
  return std::make_unique<OpenCvExtractor>(
      FeatureTypeName(FeatureTypeId::kOrb),
      cv::ORB::create(max_features, static_cast<float>(o.scale_factor), o.levels,
                      o.edge_threshold, /*firstLevel=*/0, /*WTA_K=*/2, cv::ORB::HARRIS_SCORE,
                      o.patch_size, o.fast_threshold),
      DescriptorKind::kBinary, max_features, max_depth_m);
}

std::unique_ptr<FeatureExtractor> CreateBriskExtractor(const BriskOptions& o, int max_features,
                                                       double max_depth_m) {
  o.Check();
  return std::make_unique<OpenCvExtractor>(
      FeatureTypeName(FeatureTypeId::kBrisk),
      cv::BRISK::create(o.threshold, o.octaves, static_cast<float>(o.pattern_scale)),
      DescriptorKind::kBinary, max_features, max_depth_m);
}

std::unique_ptr<FeatureExtractor> CreateKazeExtractor(const KazeOptions& o, int max_features,
                                                      double max_depth_m) {
  o.Check();
  return std::make_unique<OpenCvExtractor>(
      FeatureTypeName(FeatureTypeId::kKaze),
      cv::KAZE::create(o.extended, o.upright, static_cast<float>(o.threshold), o.octaves,
                       o.octave_layers, cv::KAZE::DIFF_PM_G2),
      DescriptorKind::kFloat, max_features, max_depth_m, /*root_sift=*/false,
      o.single_pass ? OpenCvPasses::kSinglePass : OpenCvPasses::kDetectThenCompute);
}

std::unique_ptr<FeatureExtractor> CreateAkazeExtractor(const AkazeOptions& o, int max_features,
                                                       double max_depth_m) {
  o.Check();
  return std::make_unique<OpenCvExtractor>(
      FeatureTypeName(FeatureTypeId::kAkaze),
      cv::AKAZE::create(cv::AKAZE::DESCRIPTOR_MLDB, 0, 3, static_cast<float>(o.threshold),
                        o.octaves, o.octave_layers, cv::KAZE::DIFF_PM_G2),
      DescriptorKind::kBinary, max_features, max_depth_m);
}

}  // namespace duskmap
