// Own DAISY (Tola, Lepetit, Fua, "DAISY: An Efficient Dense Descriptor
// Applied to Wide-Baseline Stereo", PAMI 2010), as OpenCV's DAISY computes it
// with its defaults (the reference's SURF/DAISY runs, RTAB-Map type 14): the
// grey image in 0..1 blurred by 0.5; per orientation o the gradient map
// G_o = max(0, d I / d o), blurred to 1.6 and then by Gaussians of growing
// sigma (sigma_i = R (i+1) / (2 Q), incrementally); the descriptor stacks the
// orientation histograms sampled at the centre and at `ring_points` points on
// each of the Q rings of radius R (i+1) / Q, zero off the image — with the
// defaults 25 histograms x 8 bins = 200 floats, raw (linear in the image's
// contrast) unless options.normalize. Runs on SURF keypoints.
#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "slam/features/feature_extractor.h"
#include "slam/features/feature_registry.h"

namespace duskmap {

// The smoothed orientation maps: layers[i] is a CV_32FC(orientations) image
// convolved with sigma_i.
struct DaisyMaps {
  std::vector<cv::Mat> layers;
};

DaisyMaps ComputeDaisyMaps(const cv::Mat& gray8, const DaisyOptions& options);

// One CV_32F row of (1 + rings * ring_points) * orientations values per
// keypoint; each histogram has unit L2 norm (or is zero) when
// options.normalize.
cv::Mat DescribeDaisy(const DaisyMaps& maps, const DaisyOptions& options,
                      const std::vector<cv::KeyPoint>& keypoints);

int DaisyDimension(const DaisyOptions& options);

class DaisyExtractor : public FeatureExtractor {
 public:
  DaisyExtractor(const DaisyOptions& daisy, const SurfOptions& surf, int max_features,
                 double max_depth_m = 0.0);
  std::string name() const override { return FeatureTypeName(FeatureTypeId::kDaisy); }
  DescriptorKind kind() const override { return DescriptorKind::kFloat; }

 protected:
  void DetectAndDescribe(const cv::Mat& gray, std::vector<cv::KeyPoint>* keypoints,
                         cv::Mat* descriptors) const override;

 private:
  DaisyOptions daisy_;
  SurfOptions surf_;
};

}  // namespace duskmap
