#include "slam/synthetic/light/sun_texels.h"

#include <cmath>

#include <gtest/gtest.h>

#include "slam/core/check.h"

namespace duskmap {
namespace {

// A 20 cm x 4 cm floor strip (x from -0.1 to 0.1 m) at z = 0, 5 mm texels.
Quad FloorStrip() {
  Quad quad;
  quad.origin_in_world = Eigen::Vector3d(-0.1, 0.0, 0.0);
  quad.u_axis = Eigen::Vector3d::UnitX();
  quad.v_axis = Eigen::Vector3d::UnitY();
  quad.size_u_m = 0.2;
  quad.size_v_m = 0.04;
  return quad;
}

// An opaque half-plane x < 0 at height `height_m`: a ray from a point on the
// floor reaches the sun if it crosses that height at x >= 0.
SunRayTest EdgeAbove(double height_m) {
  return [height_m](const Eigen::Vector3d& p, const Eigen::Vector3d& d) {
    const double t = (height_m - p.z()) / d.z();
    return p.x() + t * d.x() >= 0.0;
  };
}

TEST(SunVisibility, AnEdgeCastsThePenumbraOfTheSunsDisc) {
  const Quad quad = FloorStrip();
  const cv::Size texels(40, 8);
  const double height_m = 3.0;
  const cv::Mat v = SunVisibility(quad, texels, Eigen::Vector3d::UnitZ(), EdgeAbove(height_m));
  ASSERT_EQ(v.type(), CV_32F);
  ASSERT_EQ(v.size(), texels);
  // The penumbra's half width: the edge's height times the disc's angular radius.
  const double half_width_m = height_m * SunTexelOptions().sun_angular_radius_rad;  // 1.4 cm
  for (int c = 0; c < texels.width; ++c) {
    const double x = -0.1 + (c + 0.5) * 0.005;
    const float value = v.at<float>(4, c);
    if (x < -half_width_m - 0.005) EXPECT_EQ(value, 0.0f) << x;
    if (x > half_width_m + 0.005) EXPECT_EQ(value, 1.0f) << x;
    if (c > 0) EXPECT_GE(value, v.at<float>(4, c - 1)) << "not monotonic at " << x;
  }
  // Half the disc at the geometric edge; partly lit inside the penumbra.
  EXPECT_NEAR(0.5 * (v.at<float>(4, 19) + v.at<float>(4, 20)), 0.5, 0.1);
  EXPECT_GT(v.at<float>(4, 21), 0.55f);  // x = +0.75 cm
  EXPECT_LT(v.at<float>(4, 21), 1.0f);
  EXPECT_LT(v.at<float>(4, 18), 0.45f);  // x = -0.75 cm
  EXPECT_GT(v.at<float>(4, 18), 0.0f);
  // Every row the same (the edge runs along v).
  for (int r = 0; r < texels.height; ++r) {
    EXPECT_EQ(cv::norm(v.row(r), v.row(4), cv::NORM_INF), 0.0) << r;
  }
}

TEST(SunVisibility, ANearEdgeIsSharpAndTheTexelsAreCoverage) {
  // 1 mm above the floor the penumbra is 9 microns: only the texel the edge
  // crosses is partial, by the fraction of its area on the lit side.
  Quad shifted = FloorStrip();
  shifted.origin_in_world.x() = -0.1 + 0.00375;  // texel 19 spans -1.25 to +3.75 mm
  const cv::Mat v = SunVisibility(shifted, cv::Size(40, 8), Eigen::Vector3d::UnitZ(), EdgeAbove(0.001));
  for (int c = 0; c < 40; ++c) {
    const float expected = c < 19 ? 0.0f : c > 19 ? 1.0f : 0.75f;
    EXPECT_NEAR(v.at<float>(2, c), expected, 1e-6f) << c;
  }
}

TEST(SunVisibility, NoSunNoLightAndFullSunEverywhere) {
  const Quad quad = FloorStrip();
  const auto never = [](const Eigen::Vector3d&, const Eigen::Vector3d&) { return false; };
  const auto always = [](const Eigen::Vector3d&, const Eigen::Vector3d&) { return true; };
  EXPECT_EQ(cv::countNonZero(SunVisibility(quad, cv::Size(40, 8), Eigen::Vector3d::UnitZ(), never)), 0);
  EXPECT_EQ(cv::countNonZero(SunVisibility(quad, cv::Size(40, 8), Eigen::Vector3d::UnitZ(), always) != 1.0f), 0);
}

TEST(SunTexelOptions, OutOfRangeValuesAreRefused) {
  SunTexelOptions options;
  EXPECT_NO_THROW(options.Check());
  options.samples_per_texel = 0;
  EXPECT_THROW(options.Check(), ConfigError);
  options = SunTexelOptions();
  options.max_penumbra_m = -0.1;
  EXPECT_THROW(options.Check(), ConfigError);
  options = SunTexelOptions();
  options.sun_angular_radius_rad = 0.2;
  EXPECT_THROW(options.Check(), ConfigError);
}

}  // namespace
}  // namespace duskmap
