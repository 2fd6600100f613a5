#include "slam/eval/trajectory_error.h"

#include <gtest/gtest.h>

#include "slam/core/check.h"

namespace duskmap {
namespace {

std::vector<Rigid3d> Circle(int n) {
  std::vector<Rigid3d> poses;
  for (int i = 0; i < n; ++i) {
    const double a = 2.0 * M_PI * i / n;
    poses.emplace_back(Eigen::Quaterniond(Eigen::AngleAxisd(a, Eigen::Vector3d::UnitZ())),
                       Eigen::Vector3d(2.0 * std::cos(a), 2.0 * std::sin(a), 0.1 * i / n));
  }
  return poses;
}

TEST(ComputeAte, ZeroForRigidlyMovedTrajectory) {
  const auto truth = Circle(40);
  const Rigid3d offset(Eigen::Quaterniond(Eigen::AngleAxisd(1.2, Eigen::Vector3d::UnitZ())),
                       Eigen::Vector3d(5, -3, 1));
  std::vector<Rigid3d> estimated;
  for (const auto& p : truth) estimated.push_back(offset * p);
  const AteResult ate = ComputeAte(estimated, truth);
  EXPECT_LT(ate.rmse_m, 1e-9);
  EXPECT_EQ(ate.num_poses, 40u);
}

TEST(ComputeAte, MeasuresKnownOffsets) {
  // Alternating +-d displacements along z keep the best alignment at identity.
  const auto truth = Circle(40);
  std::vector<Rigid3d> estimated = truth;
  for (size_t i = 0; i < estimated.size(); ++i) {
    estimated[i].translation.z() += (i % 2 ? 0.03 : -0.03);
  }
  const AteResult ate = ComputeAte(estimated, truth);
  EXPECT_NEAR(ate.rmse_m, 0.03, 1e-3);
  EXPECT_NEAR(ate.median_m, 0.03, 1e-3);
  EXPECT_NEAR(ate.max_m, 0.03, 2e-3);
  EXPECT_LE(ate.mean_m, ate.rmse_m + 1e-12);
}

TEST(ComputeAte, RejectsLengthMismatch) {
  EXPECT_THROW(ComputeAte(Circle(10), Circle(11)), InputError);
}

}  // namespace
}  // namespace duskmap
