#include "slam/registration/bundle_adjustment.h"

#include <algorithm>

#include <gtest/gtest.h>

#include "tests/registration/synthetic_pair.h"
#include "tests/testing/rigid3d_near.h"

namespace duskmap {
namespace {

std::vector<BundleAdjustmentCorrespondence> MakeCorrespondences(const Rigid3d& query_from_node,
                                                                int n, uint64_t seed) {
  const PinholeCamera camera = testing::TestCamera();
  Rng rng(seed);
  std::uniform_real_distribution<double> u(50, 590), v(50, 430), z(1, 5);
  std::normal_distribution<double> noise(0.0, 0.3);
  std::vector<BundleAdjustmentCorrespondence> c;
  while (static_cast<int>(c.size()) < n) {
    const Eigen::Vector2d px(u(rng), v(rng));
    const Eigen::Vector3d p = camera.Unproject(px.x(), px.y(), z(rng));
    Eigen::Vector2d q;
    if (!camera.Project(query_from_node * p, &q)) continue;
    c.push_back({p, px, q + Eigen::Vector2d(noise(rng), noise(rng)),
                 Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN())});
  }
  return c;
}

TEST(RefineTwoViewBundleAdjustment, ConvergesFromPerturbedPoseAndDropsOutlier) {
  const PinholeCamera camera = testing::TestCamera();
  const Rigid3d truth(Eigen::Quaterniond(Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitY())),
                      Eigen::Vector3d(-0.2, 0.05, 0.1));
  std::vector<BundleAdjustmentCorrespondence> c = MakeCorrespondences(truth, 80, 1);
  c[5].pixel_in_query += Eigen::Vector2d(30.0, -25.0);  // a gross outlier
  const Rigid3d guess(
      truth.rotation * Eigen::Quaterniond(Eigen::AngleAxisd(0.01, Eigen::Vector3d::UnitX())),
      truth.translation + Eigen::Vector3d(0.02, -0.01, 0.03));
  const BundleAdjustmentResult result =
      RefineTwoViewBundleAdjustment({}, c, camera, camera, guess);
  ASSERT_TRUE(result.success);
  EXPECT_THAT(result.query_from_node, testing::Rigid3dNear(truth, 0.005, 0.1146));  // 0.002 rad
  EXPECT_EQ(std::count(result.inliers.begin(), result.inliers.end(), 5), 0);
  EXPECT_GE(result.inliers.size(), 75u);
  EXPECT_LE(result.final_cost, result.initial_cost);
}

TEST(RefineTwoViewBundleAdjustment, EmptyInputIsNotASuccess) {
  const PinholeCamera camera = testing::TestCamera();
  const BundleAdjustmentResult result =
      RefineTwoViewBundleAdjustment({}, {}, camera, camera, Rigid3d());
  EXPECT_FALSE(result.success);
  EXPECT_TRUE(result.query_from_node.IsFinite());
}

}  // namespace
}  // namespace duskmap
