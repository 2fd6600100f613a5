// One RGB-D frame as every dataset reader yields it, and the metadata of the
// session it belongs to.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include <opencv2/core.hpp>

#include "slam/core/camera.h"
#include "slam/core/rigid3.h"

namespace duskmap {

struct RgbdFrame {
  int64_t frame_index = 0;        // 0-based position in its session
  double timestamp_s = 0.0;       // seconds, monotonic within a session
  cv::Mat bgr;                    // CV_8UC3, BGR, camera.width x camera.height
  cv::Mat depth_m;                // CV_32FC1 metres registered to bgr; 0 = no depth
  PinholeCamera camera;           // intrinsics of bgr and depth_m
  Rigid3d body_from_camera;       // camera-to-body (device) transform
  Rigid3d odom_from_body;         // odometry pose of the body in its session's odometry frame
  std::optional<Rigid3d> world_from_camera;  // ground truth, when the dataset has it
  // Where the frame came from, for features imported per image (h5) and for
  // lists of the images an external extractor should read: the session's
  // name, the colour image relative to the session folder ("rgb/60360.000000.png")
  // and as the reader opened it. Empty where the dataset has no image files
  // (RTAB-Map databases hold their images as blobs).
  std::string session;
  std::string image_name;
  std::string image_file;

  Rigid3d odom_from_camera() const { return odom_from_body * body_from_camera; }
};

struct SessionInfo {
  std::string name;                       // e.g. "1", "A", "rgbd_dataset_freiburg1_desk"
  std::optional<std::string> clock_time;  // local "HH:MM" when known
  int64_t num_frames = 0;
  bool has_ground_truth = false;
};

}  // namespace duskmap
