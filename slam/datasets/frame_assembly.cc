#include "slam/datasets/frame_assembly.h"

#include <cmath>
#include <sstream>

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "slam/core/check.h"

namespace duskmap {
namespace {

bool NeedsUndistortion(const CameraCalibration& calibration) {
  return calibration.HasDistortion() ||
         (calibration.rectification &&
          !calibration.rectification->isApprox(Eigen::Matrix3d::Identity(), 1e-12));
}

cv::Mat RegisterDepth(const cv::Mat& depth_m, const cv::Size& colour_size,
                      const std::string& where) {
  if (depth_m.empty()) return cv::Mat::zeros(colour_size, CV_32FC1);
  SLAM_CHECK(depth_m.type() == CV_32FC1);
  if (depth_m.size() == colour_size) return depth_m;
  const double scaled_height = depth_m.rows * static_cast<double>(colour_size.width) / depth_m.cols;
  SLAM_THROW_IF_NOT(InputError, std::abs(scaled_height - colour_size.height) <= 1.0)
      << where << ": depth " << depth_m.cols << "x" << depth_m.rows
      << " does not have the aspect ratio of the colour image " << colour_size.width << "x"
      << colour_size.height;
  cv::Mat registered;
  cv::resize(depth_m, registered, colour_size, 0.0, 0.0, cv::INTER_NEAREST);
  return registered;
}

cv::Mat ToCvMatrix(const PinholeCamera& camera) {
  return (cv::Mat_<double>(3, 3) << camera.fx, 0.0, camera.cx, 0.0, camera.fy, camera.cy, 0.0,
          0.0, 1.0);
}

}  // namespace

void FrameAssembler::UpdateMaps(const CameraCalibration& calibration,
                                const PinholeCamera& camera) {
  std::ostringstream key;
  key.precision(17);
  key << camera.width << "x" << camera.height << " " << calibration.camera_matrix << " "
      << calibration.fisheye;
  for (double d : calibration.distortion) key << " " << d;
  if (calibration.rectification) key << " R" << *calibration.rectification;
  if (calibration.projection) key << " P" << *calibration.projection;
  if (key.str() == maps_key_) return;
  // K of the raw image, scaled like the output camera.
  PinholeCamera raw;
  raw.width = calibration.image_width;
  raw.height = calibration.image_height;
  raw.fx = calibration.camera_matrix(0, 0);
  raw.fy = calibration.camera_matrix(1, 1);
  raw.cx = calibration.camera_matrix(0, 2);
  raw.cy = calibration.camera_matrix(1, 2);
  raw = raw.Scaled(static_cast<double>(camera.width) / raw.width,
                   static_cast<double>(camera.height) / raw.height);
  cv::Mat rectification = cv::Mat::eye(3, 3, CV_64F);
  if (calibration.rectification) {
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) rectification.at<double>(r, c) = (*calibration.rectification)(r, c);
    }
  }
  const cv::Mat distortion(calibration.distortion, true);
  const cv::Size size(camera.width, camera.height);
  if (calibration.fisheye) {
    cv::fisheye::initUndistortRectifyMap(ToCvMatrix(raw), distortion, rectification,
                                         ToCvMatrix(camera), size, CV_32FC1, map_x_, map_y_);
  } else {
    cv::initUndistortRectifyMap(ToCvMatrix(raw), distortion, rectification, ToCvMatrix(camera),
                                size, CV_32FC1, map_x_, map_y_);
  }
  maps_key_ = key.str();
}

void FrameAssembler::Assemble(const cv::Mat& bgr, const cv::Mat& depth_m,
                              const CameraCalibration& calibration, const std::string& where,
                              RgbdFrame* frame) {
  SLAM_CHECK(bgr.type() == CV_8UC3);
  if (first_size_.empty()) first_size_ = bgr.size();
  SLAM_THROW_IF_NOT(InputError, bgr.size() == first_size_)
      << where << ": image is " << bgr.cols << "x" << bgr.rows << ", but the session's first is "
      << first_size_.width << "x" << first_size_.height << " (a session's images share one size)";
  frame->camera = CameraForImage(calibration, bgr.cols, bgr.rows, where);
  frame->body_from_camera = calibration.body_from_camera;
  cv::Mat depth = RegisterDepth(depth_m, bgr.size(), where);
  if (!NeedsUndistortion(calibration)) {
    frame->bgr = bgr;
    frame->depth_m = depth;
    return;
  }
  UpdateMaps(calibration, frame->camera);
  cv::remap(bgr, frame->bgr, map_x_, map_y_, cv::INTER_LINEAR, cv::BORDER_CONSTANT);
  cv::remap(depth, frame->depth_m, map_x_, map_y_, cv::INTER_NEAREST, cv::BORDER_CONSTANT);
}

}  // namespace duskmap
