#include "slam/synthetic/sensor/route.h"

#include <gtest/gtest.h>

namespace duskmap {
namespace {

TEST(GenerateRoute, StartsAndEndsFacingTheDockingPicture) {
  const Scene scene = BuildApartment(ApartmentOptions());
  for (uint64_t seed : {1, 2, 3}) {
    const std::vector<TimedPose> route = GenerateRoute(RouteOptions(), ApartmentPatrolRoute(), seed);
    for (const TimedPose* p : {&route.front(), &route.back()}) {
      const Eigen::Vector3d forward = p->world_from_camera.rotation * Eigen::Vector3d::UnitZ();
      EXPECT_GT(forward.y(), 0.99 * forward.head<2>().norm()) << "should face north, seed " << seed;
      EXPECT_LT((p->world_from_camera.translation.head<2>() - scene.docking_world_from_camera.translation.head<2>()).norm(), 0.05);
    }
  }
}

TEST(GenerateRoute, AboutTwoHundredFramesAtWalkingSpeed) {
  const std::vector<TimedPose> route = GenerateRoute(RouteOptions(), ApartmentPatrolRoute(), 4);
  EXPECT_GT(route.size(), 160u);
  EXPECT_LT(route.size(), 240u);
  double max_step = 0.0;
  for (size_t k = 1; k < route.size(); ++k) {
    EXPECT_NEAR(route[k].time_s - route[k - 1].time_s, 1.0, 1.0);
    max_step = std::max(max_step, (route[k].world_from_camera.translation - route[k - 1].world_from_camera.translation).norm());
    const double z = route[k].world_from_camera.translation.z();
    EXPECT_GT(z, 1.2);
    EXPECT_LT(z, 1.4);
  }
  EXPECT_LT(max_step, 0.55 * 1.1 + 0.1);
}

TEST(GenerateRoute, SessionsDeviateWithinTheConfiguredBounds) {
  RouteOptions nominal;
  nominal.lateral_max_m = 0.0;
  nominal.heading_max_deg = 0.0;
  nominal.speed_variation = 0.0;
  RouteOptions options;
  options.speed_variation = 0.0;  // same timing, so frames correspond one to one
  const std::vector<TimedPose> a = GenerateRoute(nominal, ApartmentPatrolRoute(), 5);
  const std::vector<TimedPose> b = GenerateRoute(options, ApartmentPatrolRoute(), 6);
  ASSERT_EQ(a.size(), b.size());
  double max_offset = 0.0, max_heading_deg = 0.0;
  for (size_t k = 0; k < a.size(); ++k) {
    max_offset = std::max(max_offset, (a[k].world_from_camera.translation - b[k].world_from_camera.translation).head<2>().norm());
    const Eigen::Vector3d fa = a[k].world_from_camera.rotation * Eigen::Vector3d::UnitZ();
    const Eigen::Vector3d fb = b[k].world_from_camera.rotation * Eigen::Vector3d::UnitZ();
    const double heading = std::abs(std::atan2(fa.x() * fb.y() - fa.y() * fb.x(), fa.head<2>().dot(fb.head<2>())));
    max_heading_deg = std::max(max_heading_deg, heading * 180.0 / M_PI);
  }
  EXPECT_GT(max_offset, 0.05);
  EXPECT_LE(max_offset, options.lateral_max_m + 1e-9);
  EXPECT_GT(max_heading_deg, 1.0);
  EXPECT_LE(max_heading_deg, options.heading_max_deg + 1e-6);
}

}  // namespace
}  // namespace duskmap
