// Own BRIEF (Calonder, Lepetit, Strecha, Fua, ECCV 2010): 8*bytes binary
// intensity tests on a Gaussian-smoothed patch, test locations drawn once
// from an isotropic Gaussian (sigma = patch/5, pattern G II of the paper)
// with a fixed seed. Not rotation-invariant by design. Runs on GFTT corners
// as RTAB-Map's GFTT/BRIEF (type 6) does.
#pragma once

#include <array>
#include <vector>

#include <opencv2/core.hpp>

#include "slam/features/feature_extractor.h"
#include "slam/features/feature_registry.h"

namespace duskmap {

// Test point pairs (x1, y1, x2, y2), offsets from the keypoint in pixels,
// inside [-patch/2 + 1, patch/2 - 1]. Deterministic for a given seed.
std::vector<std::array<int8_t, 4>> MakeBriefPattern(const BriefOptions& options);

// Bit i of row k is 1 when smoothed(p1) < smoothed(p2) for pair i.
// Keypoints must lie at least patch/2 px inside `smoothed`.
cv::Mat DescribeBrief(const cv::Mat& smoothed, const std::vector<cv::KeyPoint>& keypoints,
                      const std::vector<std::array<int8_t, 4>>& pattern);

class BriefExtractor : public FeatureExtractor {
 public:
  BriefExtractor(const BriefOptions& brief, const GfttOptions& gftt, int max_features,
                 double max_depth_m = 0.0);
  std::string name() const override { return FeatureTypeName(FeatureTypeId::kBrief); }
  DescriptorKind kind() const override { return DescriptorKind::kBinary; }

 protected:
  void DetectAndDescribe(const cv::Mat& gray, std::vector<cv::KeyPoint>* keypoints,
                         cv::Mat* descriptors) const override;

 private:
  BriefOptions brief_;
  GfttOptions gftt_;
  std::vector<std::array<int8_t, 4>> pattern_;
};

}  // namespace duskmap
