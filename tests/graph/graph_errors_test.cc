#include "slam/graph/graph_errors.h"

#include <gtest/gtest.h>

#include "tests/graph/graph_test_data.h"

namespace duskmap {
namespace {

TEST(ComputeMaxGraphErrors, RatiosUseLargestSigmaAndMaxAxis) {
  PoseGraph graph;
  graph.AddNode(1, 0, Rigid3d());
  graph.AddNode(2, 0, Rigid3d(Eigen::Quaterniond(Eigen::AngleAxisd(0.02, Eigen::Vector3d::UnitZ())),
                              Eigen::Vector3d(1.0, 0.3, 0.1)));
  graph.AddNode(3, 0, Rigid3d(Eigen::Quaterniond::Identity(), Eigen::Vector3d(2.0, 0.0, 0.0)));
  Information6d info = Information6d::Identity();
  info.diagonal() << 100, 25, 100, 1e4, 1e4, 2500;  // sigmas 0.1/0.2/0.1 m, 0.01/0.01/0.02 rad
  graph.AddLink(testing::MakeLink(1, 2, LinkType::kLoopClosure,
                                  Rigid3d(Eigen::Quaterniond::Identity(), Eigen::Vector3d(1, 0, 0)),
                                  info));
  graph.AddLink(testing::MakeLink(2, 3, LinkType::kOdometry,
                                  graph.node(2).world_from_node.Inverse() *
                                      graph.node(3).world_from_node,
                                  Information6d::Identity()));
  const MaxGraphErrors errors = ComputeMaxGraphErrors(graph);
  ASSERT_TRUE(errors.linear.found);
  EXPECT_EQ(errors.linear.link, (LinkKey{1, 2, LinkType::kLoopClosure}));
  EXPECT_NEAR(errors.linear.error, 0.3, 1e-12);         // max(|0|, |0.3|, |0.1|)
  EXPECT_NEAR(errors.linear.ratio, 0.3 / 0.2, 1e-9);    // largest sigma 0.2 m
  ASSERT_TRUE(errors.angular.found);
  EXPECT_NEAR(errors.angular.error, 0.02, 1e-9);
  EXPECT_NEAR(errors.angular.ratio, 0.02 / 0.02, 1e-6);  // largest sigma 0.02 rad
}

TEST(ComputeMaxGraphErrors, EmptyGraphHasNoLink) {
  const MaxGraphErrors errors = ComputeMaxGraphErrors(PoseGraph());
  EXPECT_FALSE(errors.linear.found);
  EXPECT_FALSE(errors.angular.found);
}

}  // namespace
}  // namespace duskmap
