#include "slam/synthetic/sensor/odometry.h"

#include "slam/core/check.h"

#include <algorithm>

#include <gtest/gtest.h>

namespace duskmap {
namespace {

// A straight 100 m walk along the camera's optical axis, 0.5 m per frame.
std::vector<Rigid3d> StraightLine(std::vector<double>* times) {
  std::vector<Rigid3d> poses;
  for (int k = 0; k <= 200; ++k) {
    poses.push_back(Rigid3d(Eigen::Quaterniond::Identity(), Eigen::Vector3d(0, 0, 0.5 * k)));
    times->push_back(k);
  }
  return poses;
}

TEST(SimulateOdometry, StartsAtIdentityAndDriftsAboutOnePercent) {
  OdometryOptions options;
  options.yaw_drift_deg_per_min = 0.0;
  std::vector<double> times;
  const std::vector<Rigid3d> truth = StraightLine(&times);
  std::vector<double> error_fraction;
  for (uint64_t seed = 1; seed <= 40; ++seed) {
    const std::vector<Rigid3d> odom = SimulateOdometry(options, truth, times, seed);
    ASSERT_EQ(odom.size(), truth.size());
    EXPECT_LT(odom.front().translation.norm(), 1e-12);
    error_fraction.push_back((odom.back().translation - truth.back().translation).norm() / 100.0);
  }
  std::sort(error_fraction.begin(), error_fraction.end());
  const double median = error_fraction[error_fraction.size() / 2];
  // Random-walk noise of 1% per step over 200 steps plus 0.5% scale error:
  // the endpoint error is a fraction of a percent, within the configured model.
  EXPECT_GT(median, 0.001);
  EXPECT_LT(median, 0.02);
  EXPECT_LT(error_fraction.back(), 0.04);
}

TEST(SimulateOdometry, YawDriftGrowsWithTime) {
  OdometryOptions options;
  options.drift_fraction = 0.0;
  options.scale_error_std = 0.0;
  options.yaw_noise_fraction = 0.0;
  options.yaw_drift_deg_per_min = 3.0;
  std::vector<double> times;
  const std::vector<Rigid3d> truth = StraightLine(&times);
  double sum_abs_yaw = 0.0;
  for (uint64_t seed = 1; seed <= 20; ++seed) {
    const std::vector<Rigid3d> odom = SimulateOdometry(options, truth, times, seed);
    const double early = odom[20].rotation.angularDistance(truth[20].rotation);
    const double late = odom[200].rotation.angularDistance(truth[200].rotation);
    EXPECT_GE(late, early);
    sum_abs_yaw += late * 180.0 / M_PI;
  }
  // 200 s at a rate with std 3 deg/min: mean |yaw| = 3 * 200/60 * sqrt(2/pi) = 8 deg.
  EXPECT_GT(sum_abs_yaw / 20, 3.0);
  EXPECT_LT(sum_abs_yaw / 20, 16.0);
}

TEST(SimulateOdometry, ZeroNoiseReproducesTheTruthInTheFirstFrame) {
  OdometryOptions options;
  options.drift_fraction = options.scale_error_std = options.yaw_drift_deg_per_min = options.yaw_noise_fraction = 0.0;
  std::vector<double> times;
  std::vector<Rigid3d> truth = StraightLine(&times);
  for (size_t k = 0; k < truth.size(); ++k) truth[k] = Rigid3d(Eigen::Quaterniond(Eigen::AngleAxisd(0.01 * k, Eigen::Vector3d::UnitY())), truth[k].translation);
  const std::vector<Rigid3d> odom = SimulateOdometry(options, truth, times, 1);
  const Rigid3d expected = truth.front().Inverse() * truth.back();
  EXPECT_LT((odom.back().translation - expected.translation).norm(), 1e-9);
}

TEST(OdometryOptions, CheckNamesTheField) {
  OdometryOptions o;
  o.drift_fraction = -1;
  EXPECT_THROW(o.Check(), ConfigError);
}

}  // namespace
}  // namespace duskmap
