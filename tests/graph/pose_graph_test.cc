#include "slam/graph/pose_graph.h"

#include <limits>

#include <gtest/gtest.h>

#include "slam/core/check.h"
#include "tests/graph/graph_test_data.h"

namespace duskmap {
namespace {

using testing::MakeLink;

TEST(PoseGraph, ComponentsOrderedByOldestNode) {
  PoseGraph graph;
  for (NodeId id = 1; id <= 6; ++id) graph.AddNode(id, id <= 3 ? 0 : 1, Rigid3d());
  graph.AddLink(MakeLink(1, 2, LinkType::kOdometry, Rigid3d(), Information6d::Identity()));
  graph.AddLink(MakeLink(2, 3, LinkType::kOdometry, Rigid3d(), Information6d::Identity()));
  graph.AddLink(MakeLink(5, 6, LinkType::kOdometry, Rigid3d(), Information6d::Identity()));
  graph.AddLink(MakeLink(6, 4, LinkType::kLoopClosure, Rigid3d(), Information6d::Identity()));
  const auto components = graph.ConnectedComponents();
  ASSERT_EQ(components.size(), 2u);
  EXPECT_EQ(components[0], (std::vector<NodeId>{1, 2, 3}));
  EXPECT_EQ(components[1], (std::vector<NodeId>{4, 5, 6}));

  graph.AddLink(MakeLink(3, 4, LinkType::kLoopClosure, Rigid3d(), Information6d::Identity()));
  EXPECT_EQ(graph.ConnectedComponents().size(), 1u);
  EXPECT_TRUE(graph.RemoveLink({3, 4, LinkType::kLoopClosure}));
  EXPECT_FALSE(graph.RemoveLink({3, 4, LinkType::kLoopClosure}));
  EXPECT_EQ(graph.ConnectedComponents().size(), 2u);
  EXPECT_EQ(graph.LinksOf(6).size(), 2u);
}

TEST(PoseGraph, RejectsBadInput) {
  PoseGraph graph;
  graph.AddNode(1, 0, Rigid3d());
  graph.AddNode(2, 0, Rigid3d());
  EXPECT_THROW(graph.AddNode(1, 0, Rigid3d()), InputError);
  EXPECT_THROW(graph.AddNode(0, 0, Rigid3d()), InputError);
  Rigid3d nan_pose;
  nan_pose.translation.x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(graph.AddNode(3, 0, nan_pose), InputError);
  EXPECT_THROW(graph.SetPose(2, nan_pose), InputError);
  EXPECT_THROW(graph.SetPose(9, Rigid3d()), InputError);
  EXPECT_THROW(graph.node(9), InputError);

  try {
    graph.AddLink(MakeLink(1, 7, LinkType::kLoopClosure, Rigid3d(), Information6d::Identity()));
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("missing node 7"), std::string::npos) << e.what();
  }
  EXPECT_THROW(graph.AddLink(MakeLink(1, 1, LinkType::kOdometry, Rigid3d(),
                                      Information6d::Identity())),
               InputError);
  EXPECT_THROW(graph.AddLink(MakeLink(1, 2, LinkType::kOdometry, nan_pose,
                                      Information6d::Identity())),
               InputError);
  Information6d singular = Information6d::Identity();
  singular(5, 5) = 0.0;
  EXPECT_THROW(graph.AddLink(MakeLink(1, 2, LinkType::kOdometry, Rigid3d(), singular)),
               InputError);
  Information6d asymmetric = Information6d::Identity();
  asymmetric(0, 1) = 0.5;
  EXPECT_THROW(graph.AddLink(MakeLink(1, 2, LinkType::kOdometry, Rigid3d(), asymmetric)),
               InputError);
  graph.AddLink(MakeLink(1, 2, LinkType::kOdometry, Rigid3d(), Information6d::Identity()));
  EXPECT_THROW(
      graph.AddLink(MakeLink(1, 2, LinkType::kOdometry, Rigid3d(), Information6d::Identity())),
      InputError);
  EXPECT_NO_THROW(
      graph.AddLink(MakeLink(1, 2, LinkType::kProximity, Rigid3d(), Information6d::Identity())));
}

}  // namespace
}  // namespace duskmap
