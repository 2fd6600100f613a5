#include "slam/retrieval/place_graph.h"

#include <gtest/gtest.h>

#include "slam/core/check.h"

namespace duskmap {
namespace {

int MarginOf(const PlaceGraph& g, NodeId from, NodeId to) {
  for (const NodeMargin& m : g.Neighbourhood(from)) {
    if (m.node == to) return m.margin;
  }
  return -1;
}

// Two sessions of 5 nodes: 1-2-3-4-5 and 11-12-13-14-15.
PlaceGraph TwoSessions() {
  PlaceGraph g(16);
  for (NodeId n = 1; n <= 5; ++n) g.AddNode(n, 0);
  for (NodeId n = 11; n <= 15; ++n) g.AddNode(n, 1);
  for (NodeId n = 1; n < 5; ++n) g.AddLink(n, n + 1, LinkType::kOdometry);
  for (NodeId n = 11; n < 15; ++n) g.AddLink(n, n + 1, LinkType::kOdometry);
  return g;
}

TEST(PlaceGraph, OdometryAddsOneLoopClosureZeroProximityNothing) {
  PlaceGraph g = TwoSessions();
  EXPECT_EQ(MarginOf(g, 1, 1), 0);
  EXPECT_EQ(MarginOf(g, 1, 4), 3);
  EXPECT_EQ(MarginOf(g, 1, 13), -1);
  g.AddLink(15, 5, LinkType::kProximity);
  EXPECT_EQ(MarginOf(g, 1, 15), -1);
  const uint64_t before = g.Version(2);
  g.AddLink(13, 3, LinkType::kLoopClosure);  // invalidates the cached neighbourhood
  EXPECT_NE(g.Version(2), before);
  EXPECT_EQ(MarginOf(g, 3, 13), 0);  // the same place across sessions
  EXPECT_EQ(MarginOf(g, 1, 13), 2);
  EXPECT_EQ(MarginOf(g, 1, 15), 4);
  EXPECT_EQ(g.OdometryNeighbours(3), (std::vector<NodeId>{2, 4}));
}

TEST(PlaceGraph, MaxMarginCutsTheNeighbourhood) {
  PlaceGraph g(2);
  for (NodeId n = 1; n <= 6; ++n) g.AddNode(n, 0);
  for (NodeId n = 1; n < 6; ++n) g.AddLink(n, n + 1, LinkType::kOdometry);
  EXPECT_EQ(g.Neighbourhood(1).size(), 3u);
  EXPECT_EQ(g.Neighbourhood(3).size(), 5u);
}

TEST(PlaceGraph, RemovalAndBadInput) {
  PlaceGraph g = TwoSessions();
  EXPECT_TRUE(g.RemoveNode(3));
  EXPECT_FALSE(g.RemoveNode(3));  // removed twice
  EXPECT_EQ(MarginOf(g, 1, 4), -1);
  EXPECT_EQ(MarginOf(g, 1, 2), 1);
  EXPECT_THROW(g.AddLink(1, 3, LinkType::kOdometry), InputError);
  EXPECT_THROW(g.AddNode(1, 0), InputError);
  EXPECT_THROW(g.Neighbourhood(99), InputError);
  EXPECT_THROW(PlaceGraph(-1), ConfigError);
}

}  // namespace
}  // namespace duskmap
