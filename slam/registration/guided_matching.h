// Second-pass matching guided by a first pose estimate (spec 6.4, reference
// Reg/RepeatOnce with Vis/CorGuessWinSize): every map point with a finite 3D
// position is projected into the query image, and matched among the query
// keypoints within a window around the projection.
//  - no candidate: no match;
//  - one candidate: accepted without a ratio test;
//  - two or more: 2-NN on descriptor distance (squared L2 / Hamming),
//    accepted when d1 < ratio * d2.
// Each query keypoint is used at most once, first come first served in map
// feature order.
#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "slam/core/camera.h"
#include "slam/core/rigid3.h"
#include "slam/features/frame_features.h"

namespace duskmap {

struct GuidedMatchingOptions {
  double window_px = 40.0;    // search radius around each projection (Vis/CorGuessWinSize)
  double float_ratio = 0.6;   // ratio on squared L2 among >= 2 candidates
  double binary_ratio = 0.8;  // ratio on Hamming distance among >= 2 candidates

  void Check() const;
};

// Matches (queryIdx into `query`, trainIdx into `map_node`). map_node must
// carry 3D points in its camera frame; query_from_node is the guess.
std::vector<cv::DMatch> MatchInProjectionWindow(const GuidedMatchingOptions& options,
                                                const FrameFeatures& map_node,
                                                const FrameFeatures& query,
                                                const PinholeCamera& query_camera,
                                                const Rigid3d& query_from_node);

}  // namespace duskmap
