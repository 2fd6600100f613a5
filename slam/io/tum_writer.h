// Writes one session in the TUM RGB-D layout: rgb/<t>.png (8-bit BGR),
// depth/<t>.png (16-bit, depth_scale units per metre, 0 = none), rgb.txt,
// depth.txt, groundtruth.txt (world_from_camera, when frames have it),
// odometry.txt (odom_from_body) and calibration.json.
#pragma once

#include <string>
#include <vector>

#include "slam/core/rgbd_frame.h"
#include "slam/io/calibration.h"
#include "slam/io/trajectory_io.h"

namespace duskmap {

class TumSessionWriter {
 public:
  // Creates `folder` with rgb/ and depth/; throws InputError when impossible.
  TumSessionWriter(const std::string& folder, const TumCalibration& calibration);

  // Writes the two images of a frame; the text files are written by Finish().
  void Write(const RgbdFrame& frame);
  // Writes the index and trajectory files and the calibration.
  void Finish();
  int64_t num_frames() const { return static_cast<int64_t>(rgb_lines_.size()); }

 private:
  std::string folder_;
  TumCalibration calibration_;
  std::vector<std::string> rgb_lines_;
  std::vector<std::string> depth_lines_;
  std::vector<TrajectoryPose> ground_truth_;
  std::vector<TrajectoryPose> odometry_;
  bool finished_ = false;
};

// Converts metres to the 16-bit raw depth image (rounded, 0 stays 0, values
// beyond the 16-bit range become 0).
cv::Mat DepthToRaw(const cv::Mat& depth_m, double depth_scale);
cv::Mat RawToDepth(const cv::Mat& raw, double depth_scale);

// "%.6f" of a timestamp, as TUM names its files.
std::string TumStamp(double timestamp_s);

}  // namespace duskmap
