#include "slam/engine/map_optimization.h"

#include <gtest/gtest.h>

namespace duskmap {
namespace {

MapNode Node(NodeId id, SessionId session, const Rigid3d& pose) {
  MapNode node;
  node.id = id;
  node.session = session;
  node.map_from_body = pose;
  return node;
}

TEST(OptimizeMap, LoopClosureBringsSecondSessionIntoFirstFrame) {
  Map map;
  map.AddSession("1", std::nullopt);
  map.AddSession("2", std::nullopt);
  const Rigid3d truth_2(Eigen::Quaterniond::Identity(), {1, 0, 0});
  map.AddNode(Node(1, 0, Rigid3d()));
  map.AddNode(Node(2, 0, truth_2));
  // Session 1 starts in its own odometry frame (far away).
  map.AddNode(Node(3, 1, Rigid3d(Eigen::Quaterniond::Identity(), {50, 50, 0})));
  Link odometry;
  odometry.from = 1;
  odometry.to = 2;
  odometry.from_from_to = truth_2;
  odometry.information *= 1e4;
  map.AddLink(odometry);
  Link loop;
  loop.from = 3;
  loop.to = 2;
  loop.type = LinkType::kLoopClosure;
  loop.from_from_to = Rigid3d(Eigen::Quaterniond::Identity(), {0.5, 0, 0});  // node 3 at x = 0.5
  loop.information *= 1e3;
  map.AddLink(loop);
  const OptimizationSummary summary = OptimizeMap(PoseGraphOptimizerOptions(), {loop}, &map);
  ASSERT_TRUE(summary.accepted()) << OptimizationStatusName(summary.status);
  EXPECT_LT((map.node(3).map_from_body.translation - Eigen::Vector3d(0.5, 0, 0)).norm(), 1e-6);
  EXPECT_LT(map.node(1).map_from_body.translation.norm(), 1e-9);  // the oldest node stays fixed
}

}  // namespace
}  // namespace duskmap
