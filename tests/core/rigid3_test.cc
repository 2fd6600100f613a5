#include "slam/core/rigid3.h"

#include <gtest/gtest.h>

namespace duskmap {
namespace {

TEST(Rigid3d, ComposeAndInverse) {
  const Rigid3d b_from_a(Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ())),
                         Eigen::Vector3d(1, 2, 3));
  const Rigid3d c_from_b(Eigen::Quaterniond(Eigen::AngleAxisd(-1.1, Eigen::Vector3d::UnitX())),
                         Eigen::Vector3d(-0.5, 0, 4));
  const Eigen::Vector3d x_in_a(0.2, -0.7, 1.5);
  const Rigid3d c_from_a = c_from_b * b_from_a;
  EXPECT_TRUE((c_from_a * x_in_a).isApprox(c_from_b * (b_from_a * x_in_a), 1e-12));
  EXPECT_TRUE((c_from_a.Inverse() * (c_from_a * x_in_a)).isApprox(x_in_a, 1e-12));
  EXPECT_TRUE(Rigid3d::FromMatrix(c_from_a.ToMatrix()).ToMatrix().isApprox(c_from_a.ToMatrix()));
}

}  // namespace
}  // namespace duskmap
