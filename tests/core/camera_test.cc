#include "slam/core/camera.h"

#include <gtest/gtest.h>

namespace duskmap {
namespace {

TEST(PinholeCamera, ProjectUnprojectRoundTrip) {
  PinholeCamera camera{640, 480, 525.0, 525.0, 319.5, 239.5};
  const Eigen::Vector3d point = camera.Unproject(100.0, 50.0, 2.5);
  Eigen::Vector2d pixel;
  ASSERT_TRUE(camera.Project(point, &pixel));
  EXPECT_NEAR(pixel.x(), 100.0, 1e-9);
  EXPECT_NEAR(pixel.y(), 50.0, 1e-9);
  EXPECT_FALSE(camera.Project(Eigen::Vector3d(0, 0, -1), &pixel));
}

}  // namespace
}  // namespace duskmap
