#include "slam/eval/alignment.h"

#include <gtest/gtest.h>

#include "slam/core/check.h"
#include "slam/core/random.h"

namespace duskmap {
namespace {

std::vector<Eigen::Vector3d> RandomPoints(int n, uint64_t seed) {
  Rng rng(seed);
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < n; ++i) points.emplace_back(u(rng), u(rng), u(rng));
  return points;
}

const Rigid3d kTargetFromSource(
    Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, -0.5).normalized())),
    Eigen::Vector3d(2.0, -1.0, 0.5));

TEST(AlignPoints, RecoversRigidTransform) {
  const auto source = RandomPoints(20, 1);
  std::vector<Eigen::Vector3d> target;
  for (const auto& p : source) target.push_back(kTargetFromSource * p);
  const AlignmentResult result = AlignPoints(source, target);
  EXPECT_NEAR(result.scale, 1.0, 1e-12);
  EXPECT_LT(result.rmse_m, 1e-9);
  EXPECT_TRUE(result.target_from_source.ToMatrix().isApprox(kTargetFromSource.ToMatrix(), 1e-9));
  EXPECT_EQ(result.num_points, 20u);
}

TEST(AlignPoints, RecoversScaleOnlyWhenAsked) {
  const auto source = RandomPoints(15, 2);
  std::vector<Eigen::Vector3d> target;
  for (const auto& p : source) target.push_back(kTargetFromSource * (2.5 * p));
  AlignmentOptions sim3;
  sim3.estimate_scale = true;
  const AlignmentResult with_scale = AlignPoints(source, target, sim3);
  EXPECT_NEAR(with_scale.scale, 2.5, 1e-9);
  EXPECT_LT(with_scale.rmse_m, 1e-9);
  EXPECT_TRUE(with_scale.Apply(source[3]).isApprox(target[3], 1e-9));
  const AlignmentResult rigid = AlignPoints(source, target);
  EXPECT_EQ(rigid.scale, 1.0);
  EXPECT_GT(rigid.rmse_m, 0.5);  // a rigid fit cannot absorb the scale
}

TEST(AlignPoints, NoisyPointsGiveNoiseLevelResidual) {
  const auto source = RandomPoints(200, 3);
  Rng rng(4);
  std::normal_distribution<double> noise(0.0, 0.01);
  std::vector<Eigen::Vector3d> target;
  for (const auto& p : source) {
    target.push_back(kTargetFromSource * p + Eigen::Vector3d(noise(rng), noise(rng), noise(rng)));
  }
  const AlignmentResult result = AlignPoints(source, target);
  EXPECT_NEAR(result.rmse_m, 0.01 * std::sqrt(3.0), 0.004);
  EXPECT_LT((result.target_from_source.translation - kTargetFromSource.translation).norm(), 0.01);
}

TEST(AlignPoints, HandlesReflectionCase) {
  // A planar set: the SVD may produce a reflection that must be corrected.
  std::vector<Eigen::Vector3d> source = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {2, 0.5, 0}};
  std::vector<Eigen::Vector3d> target;
  for (const auto& p : source) target.push_back(kTargetFromSource * p);
  const AlignmentResult result = AlignPoints(source, target);
  EXPECT_NEAR(result.target_from_source.rotation.toRotationMatrix().determinant(), 1.0, 1e-9);
  EXPECT_LT(result.rmse_m, 1e-9);
}

TEST(AlignPoints, RejectsBadInput) {
  const auto source = RandomPoints(5, 5);
  EXPECT_THROW(AlignPoints(source, RandomPoints(4, 6)), InputError);
  EXPECT_THROW(AlignPoints(RandomPoints(2, 7), RandomPoints(2, 8)), InputError);
  std::vector<Eigen::Vector3d> line = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}};
  EXPECT_THROW(AlignPoints(line, line), InputError);
  auto with_nan = source;
  with_nan[2].x() = std::nan("");
  EXPECT_THROW(AlignPoints(with_nan, source), InputError);
  AlignmentOptions bad;
  bad.min_points = 2;
  EXPECT_THROW(AlignPoints(source, source, bad), ConfigError);
}

}  // namespace
}  // namespace duskmap
