#include "slam/engine/graph_reduction.h"

#include <gtest/gtest.h>

namespace duskmap {
namespace {

Rigid3d At(double x, double y) { return Rigid3d(Eigen::Quaterniond::Identity(), {x, y, 0}); }

MapNode Node(NodeId id, SessionId session, const Rigid3d& map_from_body) {
  MapNode node;
  node.id = id;
  node.session = session;
  node.map_from_body = map_from_body;
  return node;
}

Link MakeLink(const Map& map, NodeId from, NodeId to, LinkType type, double info) {
  Link link;
  link.from = from;
  link.to = to;
  link.type = type;
  link.from_from_to = map.node(from).map_from_body.Inverse() * map.node(to).map_from_body;
  link.information = Information6d::Identity() * info;
  return link;
}

// Session 0: 1-2-3 along x; session 1: 4-5-6 along x, 5 closes a loop on 2.
Map TwoPasses() {
  Map map;
  map.AddSession("1", std::nullopt);
  map.AddSession("2", std::nullopt);
  for (NodeId id = 1; id <= 3; ++id) map.AddNode(Node(id, 0, At(id, 0)));
  for (NodeId id = 4; id <= 6; ++id) map.AddNode(Node(id, 1, At(id - 3, 0.1)));
  map.AddLink(MakeLink(map, 1, 2, LinkType::kOdometry, 100));
  map.AddLink(MakeLink(map, 2, 3, LinkType::kOdometry, 100));
  map.AddLink(MakeLink(map, 4, 5, LinkType::kOdometry, 100));
  map.AddLink(MakeLink(map, 5, 6, LinkType::kOdometry, 100));
  map.AddLink(MakeLink(map, 5, 2, LinkType::kLoopClosure, 50));
  return map;
}

TEST(ReduceNode, RemovesLoopNodeAndReattachesNeighbours) {
  Map map = TwoPasses();
  const ReductionResult result = ReduceNode(5, &map);
  ASSERT_TRUE(result.reduced);
  EXPECT_EQ(result.reduced_to, 2);
  EXPECT_FALSE(map.HasNode(5));
  EXPECT_EQ(map.nodes().size(), 5u);
  ASSERT_EQ(result.merged_links.size(), 2u);
  ASSERT_TRUE(map.HasLink(2, 4));
  ASSERT_TRUE(map.HasLink(2, 6));
  // The merged transform is L^-1 * N: node 6 seen from node 2.
  const Link& to6 = map.links().at({2, 6});
  EXPECT_EQ(to6.type, LinkType::kMerged);
  const Rigid3d expected = map.node(2).map_from_body.Inverse() * map.node(6).map_from_body;
  EXPECT_TRUE(to6.from_from_to.ToMatrix().isApprox(expected.ToMatrix(), 1e-12));
  // Chained loop (information 50) and odometry (100): covariances add.
  EXPECT_NEAR(to6.information(0, 0), 1.0 / (1.0 / 50.0 + 1.0 / 100.0), 1e-9);
  // Still one connected group of sessions.
  EXPECT_EQ(map.ConnectedSessionGroups().size(), 1u);
}

TEST(ReduceNode, KeepsAnchorsAndNodesWithoutLoops) {
  Map map = TwoPasses();
  EXPECT_TRUE(IsSessionAnchor(map, 1));
  EXPECT_TRUE(IsSessionAnchor(map, 4));
  EXPECT_FALSE(IsSessionAnchor(map, 5));
  EXPECT_FALSE(ReduceNode(6, &map).reduced);  // no loop link
  map.AddLink(MakeLink(map, 4, 1, LinkType::kLoopClosure, 50));
  EXPECT_FALSE(ReduceNode(4, &map).reduced);  // session anchor
  EXPECT_EQ(map.nodes().size(), 6u);
}

TEST(ReduceNode, RepeatedRouteShrinksToFirstPass) {
  Map map = TwoPasses();
  map.AddLink(MakeLink(map, 6, 3, LinkType::kLoopClosure, 50));
  EXPECT_TRUE(ReduceNode(5, &map).reduced);
  EXPECT_TRUE(ReduceNode(6, &map).reduced);
  EXPECT_EQ(map.NodesOfSession(1), std::vector<NodeId>{4});
  EXPECT_TRUE(map.HasLink(2, 4));
  EXPECT_EQ(map.ConnectedSessionGroups().size(), 1u);
}

}  // namespace
}  // namespace duskmap
