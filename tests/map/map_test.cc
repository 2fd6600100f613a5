#include "slam/map/map.h"

#include <gtest/gtest.h>

#include "slam/core/check.h"
#include "tests/map/test_map.h"

namespace duskmap {
namespace {

TEST(Map, AddNodesAndLinks) {
  const Map map = testing::MakeTestMap(4);
  EXPECT_EQ(map.sessions().size(), 2u);
  EXPECT_EQ(map.nodes().size(), 8u);
  EXPECT_EQ(map.links().size(), 7u);  // 3 + 3 odometry, 1 loop closure
  EXPECT_EQ(map.last_node_id(), 8);
  EXPECT_TRUE(map.HasLink(8, 2));
  EXPECT_TRUE(map.HasLink(2, 8));
  EXPECT_EQ(map.LinksOf(2).size(), 3u);
  EXPECT_EQ(map.NodesOfSession(1), (std::vector<NodeId>{5, 6, 7, 8}));
  EXPECT_EQ(map.metadata().descriptor_cv_type, CV_32F);
  EXPECT_EQ(map.metadata().descriptor_cols, 64);
}

TEST(Map, ConnectedSessionGroupsFollowLoopClosures) {
  Map map = testing::MakeTestMap(3);
  EXPECT_EQ(map.ConnectedSessionGroups(), (std::vector<std::vector<SessionId>>{{0, 1}}));
  ASSERT_TRUE(map.RemoveLink(6, 2));
  EXPECT_EQ(map.ConnectedSessionGroups(), (std::vector<std::vector<SessionId>>{{0}, {1}}));
  map.AddSession("3", std::nullopt);
  EXPECT_EQ(map.ConnectedSessionGroups().size(), 3u);
}

TEST(Map, RemoveNodeRemovesItsLinksAndKeepsIdsIncreasing) {
  Map map = testing::MakeTestMap(3);
  map.RemoveNode(6);
  EXPECT_FALSE(map.HasNode(6));
  EXPECT_FALSE(map.HasLink(5, 6));
  EXPECT_FALSE(map.HasLink(6, 2));
  EXPECT_EQ(map.links().size(), 3u);  // 1-2, 2-3, 4-5 remain
  EXPECT_EQ(map.NextNodeId(), 7);  // never reuses 6
  Rng rng(1);
  EXPECT_THROW(map.AddNode(testing::RandomNode(6, 0, 5, 64, false, rng)), InputError);
}

TEST(Map, RejectsInconsistentInput) {
  Map map = testing::MakeTestMap(2);
  Rng rng(2);
  // Unknown session.
  EXPECT_THROW(map.AddNode(testing::RandomNode(10, 5, 5, 64, false, rng)), InputError);
  // Descriptor width differs from the map's.
  EXPECT_THROW(map.AddNode(testing::RandomNode(11, 0, 5, 32, false, rng)), InputError);
  // Duplicate link in the other direction, self link, unknown node.
  Link link;
  link.from = 2;
  link.to = 1;
  EXPECT_THROW(map.AddLink(link), InputError);
  link.to = 2;
  EXPECT_THROW(map.AddLink(link), InputError);
  link.to = 99;
  EXPECT_THROW(map.AddLink(link), InputError);
  MapWords words;
  words.ids = {2, 1};
  words.descriptors = cv::Mat::zeros(2, 64, CV_32F);
  EXPECT_THROW(map.SetWords(words), InputError);
}

}  // namespace
}  // namespace duskmap
