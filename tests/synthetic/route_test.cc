#include "slam/synthetic/sensor/route.h"

#include <algorithm>
#include <string>

#include <gtest/gtest.h>

#include "slam/core/check.h"

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
  EXPECT_GT(route.size(), 180u);
  EXPECT_LT(route.size(), 225u);
  for (size_t k = 1; k < route.size(); ++k) {
    EXPECT_NEAR(route[k].time_s - route[k - 1].time_s, 1.0, 1.0);
    const double z = route[k].world_from_camera.translation.z();
    EXPECT_GT(z, 1.2);
    EXPECT_LT(z, 1.4);
  }
}

// The paper's 55 cm between consecutive 1 Hz frames holds for every step of
// every session, the fastest sessions' and the widest wander's included.
TEST(GenerateRoute, NoStepBetweenFramesIsLongerThanTheCap) {
  RouteOptions options;
  options.speed_variation = 0.2;
  options.speed_mps = options.max_step_m / 1.2 - 0.002;  // the fastest session walks at the cap
  options.lateral_max_m = 0.3;
  double largest_m = 0.0;
  for (uint64_t seed = 1; seed <= 24; ++seed) {
    const std::vector<TimedPose> route = GenerateRoute(options, ApartmentPatrolRoute(), seed);
    largest_m = std::max(largest_m, LargestStepM(route));
  }
  EXPECT_LE(largest_m, options.max_step_m);
  EXPECT_GT(largest_m, 0.5);  // near the cap, so the test would see a walk that broke it
}

TEST(GenerateRoute, ASpeedThatCouldStepFurtherIsAConfigErrorNamingTheKey) {
  RouteOptions options;
  options.speed_mps = 0.55;  // the paper's cap as the mean pace: fast sessions would break it
  try {
    options.Check();
    FAIL() << "accepted a walk of up to " << options.LargestStepBoundM() << " m per frame";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("route.speed_mps"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("route.max_step_m 0.55"), std::string::npos) << e.what();
  }
  options.speed_mps = 0.45;
  options.frame_rate_hz = 0.5;  // 2 s between frames: up to 0.99 m
  EXPECT_THROW(options.Check(), ConfigError);
  options.max_step_m = 1.0;
  EXPECT_NO_THROW(options.Check());
}

// Distance from p to the polyline through the nominal route's dense samples.
double DistanceToPath(const std::vector<TimedPose>& path, const Eigen::Vector2d& p) {
  double best = 1e9;
  for (size_t k = 1; k < path.size(); ++k) {
    const Eigen::Vector2d a = path[k - 1].world_from_camera.translation.head<2>();
    const Eigen::Vector2d b = path[k].world_from_camera.translation.head<2>();
    const double length2 = (b - a).squaredNorm();
    const double f = length2 > 0 ? std::clamp((p - a).dot(b - a) / length2, 0.0, 1.0) : 0.0;
    best = std::min(best, (a + f * (b - a) - p).norm());
  }
  return best;
}

TEST(GenerateRoute, WanderStaysWithinItsBound) {
  RouteOptions nominal;
  nominal.lateral_max_m = 0.0;
  nominal.heading_max_deg = 0.0;
  nominal.speed_variation = 0.0;
  nominal.frame_rate_hz = 10.0;
  nominal.max_step_m = 0.1;
  RouteOptions options;
  options.speed_variation = 0.0;
  const std::vector<TimedPose> path = GenerateRoute(nominal, ApartmentPatrolRoute(), 5);
  const std::vector<TimedPose> walked = GenerateRoute(options, ApartmentPatrolRoute(), 6);
  double max_offset = 0.0;
  for (const TimedPose& p : walked) {
    max_offset = std::max(max_offset, DistanceToPath(path, p.world_from_camera.translation.head<2>()));
  }
  EXPECT_GT(max_offset, 0.05);
  EXPECT_LE(max_offset, options.lateral_max_m + 1e-9);
}

TEST(GenerateRoute, HeadingDeviatesWithinItsBound) {
  RouteOptions nominal;
  nominal.lateral_max_m = 0.0;
  nominal.heading_max_deg = 0.0;
  nominal.speed_variation = 0.0;
  RouteOptions options = nominal;
  options.heading_max_deg = 5.0;  // same path and timing, so frames correspond one to one
  const std::vector<TimedPose> a = GenerateRoute(nominal, ApartmentPatrolRoute(), 5);
  const std::vector<TimedPose> b = GenerateRoute(options, ApartmentPatrolRoute(), 6);
  ASSERT_EQ(a.size(), b.size());
  double max_heading_deg = 0.0;
  for (size_t k = 0; k < a.size(); ++k) {
    const Eigen::Vector3d fa = a[k].world_from_camera.rotation * Eigen::Vector3d::UnitZ();
    const Eigen::Vector3d fb = b[k].world_from_camera.rotation * Eigen::Vector3d::UnitZ();
    const double heading = std::abs(std::atan2(fa.x() * fb.y() - fa.y() * fb.x(), fa.head<2>().dot(fb.head<2>())));
    max_heading_deg = std::max(max_heading_deg, heading * 180.0 / M_PI);
  }
  EXPECT_GT(max_heading_deg, 1.0);
  EXPECT_LE(max_heading_deg, options.heading_max_deg + 1e-6);
}

}  // namespace
}  // namespace duskmap
