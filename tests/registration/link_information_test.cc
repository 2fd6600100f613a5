#include "slam/registration/link_information.h"

#include <gtest/gtest.h>

#include "tests/registration/synthetic_pair.h"

namespace duskmap {
namespace {

TEST(ComputeLinkInformation, TwentyFifthPercentileOfSquaredErrors) {
  const PinholeCamera camera = testing::TestCamera();
  std::vector<InlierCorrespondence> inliers;
  // Query points offset along x by k mm: e_k = (k mm)^2, angle ~ k mm / 2 m.
  for (int k = 1; k <= 8; ++k) {
    const Eigen::Vector3d p(0.0, 0.0, 2.0);
    inliers.push_back({p, Eigen::Vector2d(319.5, 239.5), p + Eigen::Vector3d(k * 1e-3, 0, 0)});
  }
  const LinkCovariance cov = ComputeLinkInformation({}, inliers, camera, Rigid3d());
  // n = 8, ratio 4 -> sorted index 2 -> 3 mm.
  EXPECT_NEAR(cov.linear_variance_m2, 2.1981 * 9e-6, 1e-12);
  EXPECT_NEAR(cov.angular_variance, 2.1981 * std::atan2(3e-3, 2.0), 1e-9);
  EXPECT_NEAR(cov.information(0, 0), 1.0 / cov.linear_variance_m2, 1e-6);
  EXPECT_NEAR(cov.information(5, 5), 1.0 / cov.angular_variance, 1e-6);
  EXPECT_EQ(cov.information(0, 1), 0.0);
}

TEST(ComputeLinkInformation, MissingQueryDepthUsesScaledRayAndFloors) {
  const PinholeCamera camera = testing::TestCamera();
  const Eigen::Vector3d p(0.0, 0.0, 2.0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<InlierCorrespondence> no_depth = {
      {p, Eigen::Vector2d(319.5, 239.5), Eigen::Vector3d::Constant(nan)}};
  const LinkCovariance cov = ComputeLinkInformation({}, no_depth, camera, Rigid3d());
  EXPECT_NEAR(cov.linear_variance_m2, 2.1981 * 0.2 * 0.2, 1e-9);  // ray at 2.2 m vs 2 m
  EXPECT_NEAR(cov.angular_variance, 3e-8, 1e-15);                 // same direction: floor
  const std::vector<InlierCorrespondence> exact = {{p, Eigen::Vector2d(319.5, 239.5), p}};
  EXPECT_NEAR(ComputeLinkInformation({}, exact, camera, Rigid3d()).linear_variance_m2, 1e-8,
              1e-15);
}

}  // namespace
}  // namespace duskmap
