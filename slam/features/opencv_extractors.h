// Extractors backed by OpenCV 4.6's features2d (no xfeatures2d): SIFT, ORB,
// BRISK, KAZE and AKAZE, configured with the reference's parameters.
#pragma once

#include <opencv2/features2d.hpp>

#include "slam/features/feature_extractor.h"

namespace duskmap {

// How detection and description are called.
enum class OpenCvPasses {
  // detect, keep the strongest max_features, then compute on them: the
  // reference's order (RTAB-Map's Feature2D). OpenCV's compute builds its
  // scale space again, and for KAZE assigns other orientations than its
  // detection would (docs/engine.md, "Where KAZE's time goes").
  kDetectThenCompute,
  // one detectAndCompute, then keep the strongest max_features with their
  // descriptors: one scale space, the detector's own orientations.
  kSinglePass,
};

class OpenCvExtractor : public FeatureExtractor {
 public:
  // Smaller images give no features (OpenCV's pyramids fail on them).
  static constexpr int kMinImageSidePx = 64;

  // `root_sift` post-processes float descriptors (L1 normalise, square root).
  OpenCvExtractor(std::string name, cv::Ptr<cv::Feature2D> feature, DescriptorKind kind,
                  int max_features, double max_depth_m, bool root_sift = false,
                  OpenCvPasses passes = OpenCvPasses::kDetectThenCompute);
  std::string name() const override { return name_; }
  DescriptorKind kind() const override { return kind_; }

 protected:
  void DetectAndDescribe(const cv::Mat& gray, std::vector<cv::KeyPoint>* keypoints,
                         cv::Mat* descriptors) const override;

 private:
  std::string name_;
  cv::Ptr<cv::Feature2D> feature_;
  DescriptorKind kind_;
  bool root_sift_;
  OpenCvPasses passes_;
};

std::unique_ptr<FeatureExtractor> CreateSiftExtractor(const SiftOptions& o, int max_features,
                                                      double max_depth_m);
// The sift type's detector and descriptor: cv::SIFT with `o`'s settings.
cv::Ptr<cv::Feature2D> CreateSiftFeature2D(const SiftOptions& o, int max_features);
// The keypoints an OpenCvExtractor describes in its kDetectThenCompute
// passes: `feature`'s detections on `gray`, the strongest max_features,
// strongest first; none on an image under kMinImageSidePx. The dusknet type's
// keypoints are the sift type's this way (onnx_patch_extractor.h).
std::vector<cv::KeyPoint> DetectStrongest(cv::Feature2D& feature, const cv::Mat& gray,
                                          int max_features);
std::unique_ptr<FeatureExtractor> CreateOrbExtractor(const OrbOptions& o, int max_features,
                                                     double max_depth_m);
std::unique_ptr<FeatureExtractor> CreateBriskExtractor(const BriskOptions& o, int max_features,
                                                       double max_depth_m);
std::unique_ptr<FeatureExtractor> CreateKazeExtractor(const KazeOptions& o, int max_features,
                                                      double max_depth_m);
std::unique_ptr<FeatureExtractor> CreateAkazeExtractor(const AkazeOptions& o, int max_features,
                                                       double max_depth_m);

}  // namespace duskmap
