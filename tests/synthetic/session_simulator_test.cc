#include "slam/synthetic/session_simulator.h"

#include <cmath>

#include <gtest/gtest.h>

namespace duskmap {
namespace {

constexpr double kDeg = M_PI / 180.0;

TEST(ImageVelocityPxPerS, TurningMovesTheImageSidewaysTiltingMovesItUpOrDown) {
  PinholeCamera camera;
  camera.fx = camera.fy = 525.0;
  const Eigen::Vector3d at(1, 2, 1.3);
  const Rigid3d start(CameraRotationFromYawPitchRoll(0.0, 0.0, 0.0), at);
  const Rigid3d turned(CameraRotationFromYawPitchRoll(20 * kDeg, 0.0, 0.0), at);
  const Rigid3d tilted(CameraRotationFromYawPitchRoll(0.0, 6 * kDeg, 0.0), at);
  const cv::Vec2d turn = ImageVelocityPxPerS(start, turned, camera, 1.0);
  EXPECT_NEAR(std::abs(turn[0]), 525.0 * 20 * kDeg, 0.5);  // 183 px/s
  EXPECT_NEAR(turn[1], 0.0, 0.5);
  const cv::Vec2d tilt = ImageVelocityPxPerS(start, tilted, camera, 0.5);
  EXPECT_NEAR(tilt[0], 0.0, 0.5);
  EXPECT_NEAR(std::abs(tilt[1]), 525.0 * 6 * kDeg / 0.5, 0.5);  // 110 px/s
  const cv::Vec2d still = ImageVelocityPxPerS(start, Rigid3d(start.rotation, at + Eigen::Vector3d(0.5, 0, 0)), camera, 1.0);
  EXPECT_NEAR(cv::norm(still), 0.0, 1e-9);  // translation alone does not count
}

}  // namespace
}  // namespace duskmap
