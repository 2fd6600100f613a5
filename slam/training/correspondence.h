// Where a keypoint of view A should appear in view B, from exact depth and
// pose, and which of B's detected keypoints is that same surface point: the
// ground truth of the learned descriptor's training pairs.
//
// A keypoint's angle is OpenCV's KeyPoint::angle: degrees, the direction
// (cos, sin) in pixel coordinates (x right, y down).
#pragma once

#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "slam/core/camera.h"
#include "slam/core/rigid3.h"

namespace duskmap {

struct CorrespondenceOptions {
  double max_offset_px = 2.0;         // B's keypoint within this of the projected point
  double max_scale_ratio = 1.4;       // its size within [1/r, r] x the predicted size
  double max_angle_deg = 30.0;        // its angle within this of the predicted angle
  double occlusion_tolerance = 0.03;  // visible in B: |z_in_B - depth_B| <= this x z_in_B
  void Check() const;                 // throws ConfigError "<field>: problem"
};

// One rendered view: exact depth along the optical axis (CV_32FC1 metres,
// 0 = nothing), its camera and pose.
struct ViewGeometry {
  cv::Mat depth_m;
  PinholeCamera camera;
  Rigid3d world_from_camera;
};

enum class PredictionStatus { kVisible, kNoDepth, kBehindCamera, kOutsideImage, kOccluded };

struct PredictedKeypoint {
  PredictionStatus status = PredictionStatus::kNoDepth;
  Eigen::Vector3d point_in_world = Eigen::Vector3d::Zero();  // A's surface point
  cv::Point2f pt_in_b;     // where it projects in B
  double size_in_b = 0.0;  // KeyPoint::size scaled by depth A / depth B
  double angle_in_b_deg = 0.0;  // A's orientation carried into B, [0, 360)
};

// A's keypoint seen from B: back-projected with A's depth at its pixel,
// projected into B and checked against B's depth (occlusion). The predicted
// angle is that of A's direction, carried at A's depth (a point one size
// along it) into B.
PredictedKeypoint PredictKeypoint(const cv::KeyPoint& keypoint, const ViewGeometry& a, const ViewGeometry& b,
                                  double occlusion_tolerance);

struct KeypointMatch {
  int index_a = 0;
  int index_b = 0;
  Eigen::Vector3f point_in_world;  // A's surface point
  float offset_px = 0.0f;          // from the projected point to B's keypoint
};

// Each visible keypoint of A with the nearest keypoint of B that passes the
// offset, scale and angle tests; one B keypoint per A keypoint (the nearest
// pair first). Sorted by index_a.
std::vector<KeypointMatch> MatchKeypoints(const std::vector<cv::KeyPoint>& keypoints_a, const ViewGeometry& a,
                                          const std::vector<cv::KeyPoint>& keypoints_b, const ViewGeometry& b,
                                          const CorrespondenceOptions& options);

// The difference of two angles in degrees, in [0, 180].
double AngleDifferenceDeg(double a_deg, double b_deg);

}  // namespace duskmap
