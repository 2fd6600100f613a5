#include "slam/eval/relocalization_metrics.h"

#include <gtest/gtest.h>

#include "slam/core/check.h"

namespace duskmap {
namespace {

Rigid3d Yaw(double deg, const Eigen::Vector3d& t) {
  return Rigid3d(Eigen::Quaterniond(Eigen::AngleAxisd(deg * M_PI / 180, Eigen::Vector3d::UnitZ())),
                 t);
}

TEST(ComputePoseError, TranslationAndRotation) {
  const PoseError e = ComputePoseError(Yaw(10, {1, 0, 0}), Yaw(13, {1, 0.3, 0.4}));
  EXPECT_NEAR(e.translation_m, 0.5, 1e-12);
  EXPECT_NEAR(e.rotation_deg, 3.0, 1e-9);
}

TEST(ClassifyRelocalization, UsesMapToTruthAlignmentAndThresholds) {
  const Rigid3d truth_from_map = Yaw(90, {10, 0, 0});
  const Rigid3d truth_from_camera = Yaw(30, {1, 2, 0});
  const Rigid3d map_from_camera_exact = truth_from_map.Inverse() * truth_from_camera;
  RelocalizationMetricsOptions options;
  auto check = ClassifyRelocalization(truth_from_map, map_from_camera_exact, truth_from_camera,
                                      options);
  EXPECT_TRUE(check.correct);
  EXPECT_TRUE(check.within[0] && check.within[1] && check.within[2]);

  // 0.3 m off: outside 0.25 m/2 deg, inside 0.5 m/5 deg.
  const Rigid3d off_30cm = map_from_camera_exact * Yaw(0, {0.3, 0, 0});
  check = ClassifyRelocalization(truth_from_map, off_30cm, truth_from_camera, options);
  EXPECT_NEAR(check.error.translation_m, 0.3, 1e-9);
  EXPECT_FALSE(check.within[0]);
  EXPECT_TRUE(check.within[1]);
  EXPECT_TRUE(check.correct);

  // 7 degrees off: wrong by default, within the loose threshold.
  const Rigid3d off_7deg = map_from_camera_exact * Yaw(7, {0, 0, 0});
  check = ClassifyRelocalization(truth_from_map, off_7deg, truth_from_camera, options);
  EXPECT_FALSE(check.correct);
  EXPECT_TRUE(check.within[2]);
  options.correct_threshold_index = 2;
  EXPECT_TRUE(ClassifyRelocalization(truth_from_map, off_7deg, truth_from_camera, options).correct);
}

TEST(AlignMapToTruth, RecoversMapFrame) {
  const Rigid3d truth_from_map = Yaw(-40, {3, 1, 0.5});
  std::vector<Rigid3d> map_poses, truth_poses;
  for (int i = 0; i < 10; ++i) {
    map_poses.push_back(Yaw(i * 20, {0.5 * i, std::sin(i), 0.1 * (i % 3)}));
    truth_poses.push_back(truth_from_map * map_poses.back());
  }
  const Rigid3d estimated = AlignMapToTruth(map_poses, truth_poses);
  EXPECT_TRUE(estimated.ToMatrix().isApprox(truth_from_map.ToMatrix(), 1e-9));
  truth_poses.pop_back();
  EXPECT_THROW(AlignMapToTruth(map_poses, truth_poses), InputError);
}

TEST(AlignMapToTruth, StraightRouteUsesOrientations) {
  // Collinear positions leave the roll about the line free; orientations fix it.
  const Rigid3d truth_from_map(
      Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX())), {1, 2, 3});
  std::vector<Rigid3d> map_poses, truth_poses;
  for (int i = 0; i < 5; ++i) {
    map_poses.push_back(Yaw(i * 3, {1.0 * i, 0, 0}));
    truth_poses.push_back(truth_from_map * map_poses.back());
  }
  EXPECT_TRUE(AlignMapToTruth(map_poses, truth_poses)
                  .ToMatrix()
                  .isApprox(truth_from_map.ToMatrix(), 1e-9));
}

TEST(SummarizeRelocalizations, CountsWrongSeparately) {
  RelocalizationCheck good, wrong;
  good.correct = true;
  good.within = {true, true, true};
  wrong.correct = false;
  wrong.within = {false, false, true};
  const auto summary = SummarizeRelocalizations(10, {good, good, wrong});
  EXPECT_EQ(summary.num_relocalized, 3);
  EXPECT_EQ(summary.num_correct, 2);
  EXPECT_EQ(summary.num_wrong, 1);
  EXPECT_EQ(summary.num_within[2], 3);
  EXPECT_DOUBLE_EQ(summary.relocalized_pct, 30.0);
  EXPECT_DOUBLE_EQ(summary.correct_pct, 20.0);
  EXPECT_THROW(SummarizeRelocalizations(1, {good, good}), InputError);
}

TEST(RelocalizationMetricsOptions, CheckNamesField) {
  RelocalizationMetricsOptions options;
  options.correct_threshold_index = 3;
  try {
    options.Check();
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("correct_threshold_index"), std::string::npos);
  }
}

}  // namespace
}  // namespace duskmap
