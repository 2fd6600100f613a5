#include "slam/engine/localization_evaluation.h"

#include <gtest/gtest.h>

#include "slam/core/check.h"

namespace duskmap {
namespace {

// A one-session map whose frame is the truth frame rotated by 90 deg and shifted.
Map MapWithTruth(const Rigid3d& truth_from_map) {
  Map map;
  map.AddSession("1", std::nullopt);
  for (NodeId id = 1; id <= 6; ++id) {
    MapNode node;
    node.id = id;
    node.map_from_body = Rigid3d(Eigen::Quaterniond::Identity(),
                                 {0.5 * id, std::sin(id), 0.1 * (id % 2)});
    node.truth_from_camera = truth_from_map * node.map_from_body;
    map.AddNode(node);
  }
  return map;
}

TEST(EvaluateLocalization, ClassifiesCorrectAndWrong) {
  const Rigid3d truth_from_map(
      Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ())), {3, 0, 0});
  const Map map = MapWithTruth(truth_from_map);
  std::vector<LocalizationRecord> records(4);
  std::vector<std::optional<Rigid3d>> truth(4);
  std::vector<Eigen::Vector3d> positions;
  for (int i = 0; i < 4; ++i) {
    const Rigid3d true_pose(Eigen::Quaterniond::Identity(), {i * 0.5, 0, 0});
    truth[i] = true_pose;
    positions.emplace_back(i * 0.5, 0, 0);
    records[i].frame_index = i;
  }
  // Frame 1: exact; frame 3: 1 m off (wrong); frames 0 and 2 not re-localized.
  for (int i : {1, 3}) {
    records[i].relocalized = true;
    records[i].matched_session = 0;
    records[i].inliers = 30;
    records[i].map_from_camera = truth_from_map.Inverse() * *truth[i];
  }
  records[3].map_from_camera->translation += Eigen::Vector3d(1.0, 0, 0);
  records[3].jump_mm = 1000.0;
  for (int i : {1, 3}) records[i].matched_node = 2;
  const LocalizationSummary summary = EvaluateLocalization(
      map, truth, positions, RelocalizationMetricsOptions(), &records, TruthAlignment::kWholeMap);
  EXPECT_TRUE(summary.evaluated);
  EXPECT_EQ(summary.relocalization.num_relocalized, 2);
  EXPECT_EQ(summary.relocalization.num_correct, 1);
  EXPECT_EQ(summary.relocalization.num_wrong, 1);
  ASSERT_TRUE(records[1].check.has_value());
  EXPECT_LT(records[1].check->error.translation_m, 1e-9);
  EXPECT_FALSE(records[3].check->correct);
  EXPECT_DOUBLE_EQ(summary.mean_inliers, 30.0);
  EXPECT_DOUBLE_EQ(summary.mean_jump_mm, 1000.0);
  EXPECT_DOUBLE_EQ(summary.gaps.max_gap_m, 1.0);  // frame 1 -> frame 3
}

TEST(EvaluateLocalization, MatchedNodeAlignmentIgnoresDistantMapDrift) {
  const Rigid3d truth_from_map(Eigen::Quaterniond::Identity(), {1, 0, 0});
  Map map = MapWithTruth(truth_from_map);
  // Node 6's map pose drifted by 10 deg: a whole-map alignment blames the
  // re-localization, the matched-node alignment does not.
  MapNode& drifted = map.mutable_node(6);
  drifted.map_from_body = drifted.map_from_body *
      Rigid3d(Eigen::Quaterniond(Eigen::AngleAxisd(0.17, Eigen::Vector3d::UnitZ())), {0, 0, 0});
  const Rigid3d node_from_camera(Eigen::Quaterniond::Identity(), {0.2, 0, 0.1});
  std::vector<LocalizationRecord> records(1);
  records[0].relocalized = true;
  records[0].matched_node = 6;
  records[0].matched_session = 0;
  records[0].map_from_camera = drifted.map_from_camera() * node_from_camera;
  const std::vector<std::optional<Rigid3d>> truth = {*drifted.truth_from_camera * node_from_camera};
  const std::vector<Eigen::Vector3d> positions = {Eigen::Vector3d::Zero()};
  EvaluateLocalization(map, truth, positions, RelocalizationMetricsOptions(), &records);
  EXPECT_TRUE(records[0].check->correct);
  EvaluateLocalization(map, truth, positions, RelocalizationMetricsOptions(), &records,
                       TruthAlignment::kWholeMap);
  EXPECT_FALSE(records[0].check->correct) << records[0].check->error.rotation_deg << " deg, "
                                          << records[0].check->error.translation_m << " m";
}

TEST(EvaluateLocalization, RejectsSizeMismatch) {
  const Map map = MapWithTruth(Rigid3d());
  std::vector<LocalizationRecord> records(2);
  EXPECT_THROW(EvaluateLocalization(map, {std::nullopt}, {{0, 0, 0}, {1, 0, 0}},
                                    RelocalizationMetricsOptions(), &records),
               InputError);
}

}  // namespace
}  // namespace duskmap
