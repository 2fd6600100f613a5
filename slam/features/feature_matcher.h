// Matches the features of a query frame against those of a map node. The
// nearest-neighbour ratio matcher (registration/) and the SuperGlue matcher
// (features/) both implement it, so registration can use either.
#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "slam/features/frame_features.h"

namespace duskmap {

class FeatureMatcher {
 public:
  virtual ~FeatureMatcher() = default;
  virtual std::string name() const = 0;
  // One DMatch per accepted correspondence: queryIdx indexes `query`,
  // trainIdx indexes `train`. Image sizes are needed by learned matchers that
  // normalise keypoint coordinates.
  virtual std::vector<cv::DMatch> Match(const FrameFeatures& query, const cv::Size& query_image,
                                        const FrameFeatures& train,
                                        const cv::Size& train_image) const = 0;
};

}  // namespace duskmap
