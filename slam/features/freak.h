// Own FREAK (Alahi, Ortiz, Vandergheynst, "FREAK: Fast Retina Keypoint",
// CVPR 2012): 43 receptive fields on 7 rings of 6 plus the centre, each
// smoothed over a box of its own size; orientation from 45 long-range,
// centre-symmetric pairs; 512 intensity comparisons (64 bytes).
//
// Pair table: the paper learns its 512 pairs on training images. duskmap
// instead derives a fixed, documented table (coarse to fine, the order the
// paper's learned pairs show): all 903 field pairs sorted by the smaller of
// their two field sizes (descending), then by the distance between the
// fields (descending), then by index; the first 512 are used. The 45
// orientation pairs are the 45 pairs with the largest field distance.
#pragma once

#include <array>
#include <vector>

#include <opencv2/core.hpp>

#include "slam/features/feature_extractor.h"
#include "slam/features/feature_registry.h"
#include "slam/features/integral_image.h"

namespace duskmap {

struct FreakPattern {
  static constexpr int kFields = 43;
  static constexpr int kPairs = 512;
  static constexpr int kOrientationPairs = 45;
  // Field centres and smoothing sigmas, in units of pattern_scale.
  std::array<cv::Point2f, kFields> centers;
  std::array<float, kFields> sigmas;
  std::vector<std::array<uint8_t, 2>> pairs;              // kPairs descriptor tests
  std::vector<std::array<uint8_t, 2>> orientation_pairs;  // kOrientationPairs
};

const FreakPattern& GetFreakPattern();

// Descriptors (64 bytes) of keypoints whose pattern fits inside the image;
// keypoints that do not fit are removed. Sets KeyPoint.angle when
// options.orientation_normalized.
cv::Mat DescribeFreak(const IntegralImage& integral, const FreakOptions& options,
                      std::vector<cv::KeyPoint>* keypoints);

class FreakExtractor : public FeatureExtractor {
 public:
  FreakExtractor(const FreakOptions& freak, const GfttOptions& gftt, const FastOptions& fast,
                 int max_features, double max_depth_m = 0.0);
  std::string name() const override { return FeatureTypeName(FeatureTypeId::kFreak); }
  DescriptorKind kind() const override { return DescriptorKind::kBinary; }

 protected:
  void DetectAndDescribe(const cv::Mat& gray, std::vector<cv::KeyPoint>* keypoints,
                         cv::Mat* descriptors) const override;

 private:
  FreakOptions freak_;
  GfttOptions gftt_;
  FastOptions fast_;
};

}  // namespace duskmap
