#include "slam/datasets/frame_assembly.h"

#include <gtest/gtest.h>

#include <set>

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "tests/datasets/dataset_test_util.h"

namespace duskmap {
namespace {

using testing::ErrorOf;

CameraCalibration Calibration() {
  CameraCalibration c;
  c.image_width = 64;
  c.image_height = 48;
  c.camera_matrix << 50.0, 0.0, 31.5, 0.0, 50.0, 23.5, 0.0, 0.0, 1.0;
  return c;
}

TEST(FrameAssembler, RegistersLowResolutionDepthAndKeepsColourIntrinsics) {
  const cv::Mat bgr(48, 64, CV_8UC3, cv::Scalar::all(5));
  cv::Mat depth(24, 32, CV_32FC1, cv::Scalar(2.0f));
  depth.at<float>(0, 0) = 0.0f;
  FrameAssembler assembler;
  RgbdFrame frame;
  assembler.Assemble(bgr, depth, Calibration(), "f", &frame);
  ASSERT_EQ(frame.depth_m.size(), bgr.size());
  EXPECT_EQ(frame.depth_m.at<float>(1, 1), 0.0f);  // nearest neighbour: no blending
  EXPECT_EQ(frame.depth_m.at<float>(2, 2), 2.0f);
  EXPECT_DOUBLE_EQ(frame.camera.fx, 50.0);
  RgbdFrame no_depth;
  assembler.Assemble(bgr, cv::Mat(), Calibration(), "f", &no_depth);
  EXPECT_EQ(cv::countNonZero(no_depth.depth_m), 0);
  EXPECT_EQ(ErrorOf([&] { assembler.Assemble(bgr, cv::Mat(48, 48, CV_32FC1), Calibration(), "f", &frame); }),
            "f: depth 48x48 does not have the aspect ratio of the colour image 64x48");
}

// A frame of another size than the session's first was scaled to intrinsics
// of its own without a word (1x1 in a 64x48 session is within the one-pixel
// aspect tolerance).
TEST(FrameAssembler, FrameOfAnotherSizeThanTheFirstIsRefused) {
  FrameAssembler assembler;
  RgbdFrame frame;
  assembler.Assemble(cv::Mat(48, 64, CV_8UC3, cv::Scalar::all(5)), cv::Mat(), Calibration(), "f0", &frame);
  EXPECT_EQ(ErrorOf([&] {
              assembler.Assemble(cv::Mat(1, 1, CV_8UC3, cv::Scalar::all(5)), cv::Mat(), Calibration(), "f1", &frame);
            }),
            "f1: image is 1x1, but the session's first is 64x48 (a session's images share one size)");
  EXPECT_EQ(ErrorOf([&] {
              assembler.Assemble(cv::Mat(48, 64, CV_8UC3, cv::Scalar::all(5)), cv::Mat(), Calibration(), "f2", &frame);
            }),
            "");
}

TEST(FrameAssembler, UndistortsColourAndDepth) {
  CameraCalibration c = Calibration();
  c.distortion = {0.3, 0.0, 0.0, 0.0, 0.0};
  cv::Mat bgr(48, 64, CV_8UC3, cv::Scalar::all(0));
  bgr(cv::Rect(54, 40, 2, 2)).setTo(cv::Scalar::all(255));  // a spot near the corner
  const cv::Mat depth(48, 64, CV_32FC1, cv::Scalar(1.5f));
  FrameAssembler assembler;
  RgbdFrame frame;
  assembler.Assemble(bgr, depth, c, "f", &frame);
  // Where OpenCV says the spot's centre goes once undistorted (same K).
  const cv::Mat k = (cv::Mat_<double>(3, 3) << 50, 0, 31.5, 0, 50, 23.5, 0, 0, 1);
  std::vector<cv::Point2f> distorted = {{54.5f, 40.5f}}, undistorted;
  cv::undistortPoints(distorted, undistorted, k, c.distortion, cv::noArray(), k);
  cv::Mat grey;
  cv::cvtColor(frame.bgr, grey, cv::COLOR_BGR2GRAY);
  cv::Point brightest;
  cv::minMaxLoc(grey, nullptr, nullptr, nullptr, &brightest);
  EXPECT_GT(cv::norm(cv::Point2f(brightest) - distorted[0]), 2.0);  // it moved
  EXPECT_LT(cv::norm(cv::Point2f(brightest) - undistorted[0]), 1.5);
  // Depth is remapped by nearest neighbour: only 1.5 or 0 (outside the view).
  int zeros = 0;
  for (auto it = frame.depth_m.begin<float>(); it != frame.depth_m.end<float>(); ++it) {
    EXPECT_TRUE(*it == 0.0f || *it == 1.5f);
    zeros += *it == 0.0f;
  }
  EXPECT_GT(zeros, 0);
  EXPECT_EQ(frame.depth_m.at<float>(24, 32), 1.5f);
}

}  // namespace
}  // namespace duskmap
