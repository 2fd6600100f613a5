// Turns decoded images and their calibration into an RgbdFrame:
//  - intrinsics come from the calibration, scaled when the colour image is a
//    uniformly resized version of the calibrated size (else InputError);
//  - depth at another resolution with the same aspect ratio is registered to
//    the colour image by nearest-neighbour resizing (phones record depth at a
//    lower resolution); a missing depth becomes all zeros;
//  - a distorted (or rectified) camera is undistorted: colour bilinearly, depth
//    with nearest-neighbour, to the pinhole intrinsics of K (or P when present).
// The undistortion maps are cached for the last calibration and image size.
// One assembler serves one session: every image must have the size of its
// first (a 1x1 frame in a 320x240 session was scaled to intrinsics of its own).
#pragma once

#include <string>

#include <opencv2/core.hpp>

#include "slam/core/rgbd_frame.h"
#include "slam/datasets/camera_calibration.h"

namespace duskmap {

class FrameAssembler {
 public:
  // Sets bgr, depth_m, camera and body_from_camera of *frame. `bgr` is
  // CV_8UC3; `depth_m` is CV_32FC1 or empty. `where` names the frame in errors.
  void Assemble(const cv::Mat& bgr, const cv::Mat& depth_m, const CameraCalibration& calibration,
                const std::string& where, RgbdFrame* frame);

 private:
  void UpdateMaps(const CameraCalibration& calibration, const PinholeCamera& camera);

  cv::Mat map_x_, map_y_;
  std::string maps_key_;
  cv::Size first_size_;  // of the session's first image; empty before it
};

}  // namespace duskmap
