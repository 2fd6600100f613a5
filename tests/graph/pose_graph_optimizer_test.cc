#include "slam/graph/pose_graph_optimizer.h"

#include <gtest/gtest.h>

#include "slam/core/check.h"
#include "tests/graph/graph_test_data.h"

namespace duskmap {
namespace {

using testing::CirclePose;
using testing::DiagonalInformation;
using testing::MakeLink;

constexpr int kLoopNodes = 40;
constexpr double kRadiusM = 3.0;

double MeanPositionError(const PoseGraph& graph, const std::vector<Rigid3d>& truth,
                         NodeId first_id) {
  double sum = 0.0;
  for (size_t k = 0; k < truth.size(); ++k) {
    sum += (graph.node(first_id + k).world_from_node.translation - truth[k].translation).norm();
  }
  return sum / truth.size();
}

struct OdometryModel {
  double yaw_bias_rad = 0.5 * M_PI / 180.0;  // drift per step
  double noise_m = 0.005;                    // per-step translation noise
  double noise_rad = 0.002;                  // per-step rotation noise
  double sigma_m = 0.05;                     // stated in the link information
  double sigma_rad = 0.01;
};

// One session around a circle with drifting odometry; node poses are the
// integrated odometry. Returns the ground truth.
std::vector<Rigid3d> AddDriftingLoop(PoseGraph* graph, NodeId first_id, SessionId session,
                                     const Rigid3d& odom_from_world, uint64_t seed,
                                     const OdometryModel& model = {}) {
  Rng rng(seed);
  std::vector<Rigid3d> truth;
  for (int k = 0; k < kLoopNodes; ++k) truth.push_back(CirclePose(k, kLoopNodes, kRadiusM));
  Rigid3d pose = odom_from_world * truth[0];
  graph->AddNode(first_id, session, pose);
  for (int k = 1; k < kLoopNodes; ++k) {
    const Rigid3d measured = testing::DriftedMotion(
        truth[k - 1].Inverse() * truth[k], model.yaw_bias_rad, model.noise_m, model.noise_rad, &rng);
    pose = pose * measured;
    graph->AddNode(first_id + k, session, pose);
    graph->AddLink(MakeLink(first_id + k - 1, first_id + k, LinkType::kOdometry, measured,
                            DiagonalInformation(model.sigma_m, model.sigma_rad)));
  }
  return truth;
}

TEST(OptimizePoseGraph, LoopClosureCorrectsDrift) {
  PoseGraph graph;
  const std::vector<Rigid3d> truth = AddDriftingLoop(&graph, 1, 0, Rigid3d(), 1);
  const double error_before = MeanPositionError(graph, truth, 1);
  const Link closure = MakeLink(kLoopNodes, 1, LinkType::kLoopClosure,
                                truth.back().Inverse() * truth.front(),
                                DiagonalInformation(0.01, 0.005));
  graph.AddLink(closure);
  const OptimizationSummary summary = OptimizePoseGraph({}, {KeyOf(closure)}, &graph);
  ASSERT_TRUE(summary.accepted()) << OptimizationStatusName(summary.status);
  const double error_after = MeanPositionError(graph, truth, 1);
  EXPECT_GT(error_before, 0.5);
  EXPECT_LT(error_after, 0.25 * error_before);
  EXPECT_LT(error_after, 0.15);
  // The oldest node is the fixed root.
  EXPECT_EQ(graph.node(1).world_from_node.translation, truth[0].translation);
  EXPECT_LT(summary.final_cost, summary.initial_cost);
  EXPECT_EQ(summary.num_components, 1);
  EXPECT_LT(summary.max_errors.linear.ratio, 3.0);
  EXPECT_TRUE(summary.removed_links.empty());
}

TEST(OptimizePoseGraph, TwoSessionsJoinInOlderSessionFrame) {
  PoseGraph graph;
  // Session 0's odometry frame is the world; session 1 starts in its own frame.
  OdometryModel exact;
  exact.yaw_bias_rad = exact.noise_m = exact.noise_rad = 0.0;
  const std::vector<Rigid3d> truth0 = AddDriftingLoop(&graph, 1, 0, Rigid3d(), 2, exact);
  const Rigid3d odom1_from_world(
      Eigen::Quaterniond(Eigen::AngleAxisd(2.0, Eigen::Vector3d(0.1, 0.2, 1.0).normalized())),
      Eigen::Vector3d(10.0, -4.0, 1.0));
  const NodeId first1 = 101;
  const std::vector<Rigid3d> truth1 = AddDriftingLoop(&graph, first1, 1, odom1_from_world, 3, exact);

  // Not connected yet: each session keeps its own frame.
  const Rigid3d session1_root_before = graph.node(first1).world_from_node;
  OptimizationSummary summary = OptimizePoseGraph({}, {}, &graph);
  ASSERT_TRUE(summary.accepted());
  EXPECT_EQ(summary.num_components, 2);
  EXPECT_EQ(graph.node(first1).world_from_node.translation, session1_root_before.translation);
  EXPECT_GT(MeanPositionError(graph, truth1, first1), 5.0);

  // One loop closure from session 1 (node 110) to session 0 (node 10).
  const Link closure = MakeLink(first1 + 9, 10, LinkType::kLoopClosure,
                                truth1[9].Inverse() * truth0[9], DiagonalInformation(0.01, 0.005));
  graph.AddLink(closure);
  summary = OptimizePoseGraph({}, {KeyOf(closure)}, &graph);
  ASSERT_TRUE(summary.accepted()) << OptimizationStatusName(summary.status);
  EXPECT_EQ(summary.num_components, 1);
  EXPECT_EQ(graph.node(1).world_from_node.translation, truth0[0].translation);
  EXPECT_LT(MeanPositionError(graph, truth0, 1), 1e-3);
  EXPECT_LT(MeanPositionError(graph, truth1, first1), 1e-3);
  for (size_t k = 0; k < truth1.size(); ++k) {
    EXPECT_LT(RotationAngleRad(graph.node(first1 + k).world_from_node.rotation,
                               truth1[k].rotation),
              1e-3);
  }
}

TEST(OptimizePoseGraph, WrongLoopClosureIsRejectedAndRemoved) {
  PoseGraph graph;
  OdometryModel good_odometry;  // no bias, sigmas matching the noise
  good_odometry.yaw_bias_rad = 0.0;
  good_odometry.sigma_m = 0.01;
  good_odometry.sigma_rad = 0.003;
  const std::vector<Rigid3d> truth = AddDriftingLoop(&graph, 1, 0, Rigid3d(), 4, good_odometry);
  const Link good = MakeLink(kLoopNodes, 1, LinkType::kLoopClosure,
                             truth.back().Inverse() * truth.front(),
                             DiagonalInformation(0.01, 0.005));
  graph.AddLink(good);
  ASSERT_TRUE(OptimizePoseGraph({}, {KeyOf(good)}, &graph).accepted());
  std::vector<Rigid3d> poses_before;
  for (const auto& [id, node] : graph.nodes()) poses_before.push_back(node.world_from_node);

  // Claims node 20 is 1.5 m beside where it is relative to node 5.
  const Rigid3d wrong_motion =
      truth[4].Inverse() * truth[19] *
      Rigid3d(Eigen::Quaterniond::Identity(), Eigen::Vector3d(1.5, 0.0, 0.0));
  const Link wrong =
      MakeLink(5, 20, LinkType::kLoopClosure, wrong_motion, DiagonalInformation(0.01, 0.005));
  graph.AddLink(wrong);
  const OptimizationSummary summary = OptimizePoseGraph({}, {KeyOf(wrong)}, &graph);
  EXPECT_EQ(summary.status, OptimizationStatus::kRejectedMaxError);
  EXPECT_GT(summary.max_errors.linear.ratio, 3.0);
  ASSERT_EQ(summary.removed_links.size(), 1u);
  EXPECT_EQ(summary.removed_links[0], KeyOf(wrong));
  EXPECT_FALSE(graph.HasLink(KeyOf(wrong)));
  size_t k = 0;
  for (const auto& [id, node] : graph.nodes()) {
    EXPECT_EQ(node.world_from_node.translation, poses_before[k++].translation);
  }

  // With the check disabled the same link is accepted (and distorts the map).
  graph.AddLink(wrong);
  PoseGraphOptimizerOptions no_check;
  no_check.max_error_ratio = 0.0;
  EXPECT_TRUE(OptimizePoseGraph(no_check, {KeyOf(wrong)}, &graph).accepted());
}

TEST(OptimizePoseGraph, RobustLossLimitsWrongClosureInfluence) {
  PoseGraph plain_graph;
  OdometryModel unbiased;
  unbiased.yaw_bias_rad = 0.0;
  const std::vector<Rigid3d> truth = AddDriftingLoop(&plain_graph, 1, 0, Rigid3d(), 5, unbiased);
  plain_graph.AddLink(MakeLink(kLoopNodes, 1, LinkType::kLoopClosure,
                               truth.back().Inverse() * truth.front(),
                               DiagonalInformation(0.01, 0.005)));
  const Link wrong = MakeLink(5, 20, LinkType::kLoopClosure,
                              truth[4].Inverse() * truth[19] *
                                  Rigid3d(Eigen::Quaterniond::Identity(), Eigen::Vector3d(1.5, 0, 0)),
                              DiagonalInformation(0.01, 0.005));
  plain_graph.AddLink(wrong);
  PoseGraph robust_graph = plain_graph;
  PoseGraphOptimizerOptions plain, robust;
  plain.max_error_ratio = robust.max_error_ratio = 0.0;
  plain.max_iterations = robust.max_iterations = 50;
  robust.robust_loss = RobustLoss::kCauchy;
  ASSERT_TRUE(OptimizePoseGraph(plain, {}, &plain_graph).accepted());
  ASSERT_TRUE(OptimizePoseGraph(robust, {}, &robust_graph).accepted());
  EXPECT_LT(MeanPositionError(robust_graph, truth, 1),
            0.5 * MeanPositionError(plain_graph, truth, 1));
}

TEST(OptimizePoseGraph, EmptyGraphAndBadArguments) {
  PoseGraph graph;
  const OptimizationSummary summary = OptimizePoseGraph({}, {}, &graph);
  EXPECT_EQ(summary.status, OptimizationStatus::kEmptyGraph);
  EXPECT_STREQ(OptimizationStatusName(summary.status), "empty_graph");
  graph.AddNode(1, 0, Rigid3d());
  EXPECT_TRUE(OptimizePoseGraph({}, {}, &graph).accepted());  // a lone node stays put
  EXPECT_THROW(OptimizePoseGraph({}, {{1, 2, LinkType::kLoopClosure}}, &graph), InputError);
  PoseGraphOptimizerOptions bad;
  bad.max_iterations = 0;
  EXPECT_THROW(OptimizePoseGraph(bad, {}, &graph), ConfigError);
}

TEST(InitializePosesFromLinks, PrefersOdometryChains) {
  PoseGraph graph;
  for (NodeId id = 1; id <= 3; ++id) graph.AddNode(id, 0, Rigid3d());
  const Rigid3d step(Eigen::Quaterniond::Identity(), Eigen::Vector3d(1, 0, 0));
  graph.AddLink(MakeLink(1, 2, LinkType::kOdometry, step, Information6d::Identity()));
  graph.AddLink(MakeLink(2, 3, LinkType::kOdometry, step, Information6d::Identity()));
  // A (wrong) direct closure 1 -> 3 must not be used to place node 3.
  graph.AddLink(MakeLink(1, 3, LinkType::kLoopClosure, step, Information6d::Identity()));
  InitializePosesFromLinks(&graph);
  EXPECT_NEAR(graph.node(3).world_from_node.translation.x(), 2.0, 1e-12);
}

TEST(LinksJoinComponents, OnlyALinkBetweenUnconnectedPartsJoins) {
  PoseGraph graph;
  for (NodeId id = 1; id <= 4; ++id) graph.AddNode(id, id <= 2 ? 0 : 1, Rigid3d());
  const Rigid3d step(Eigen::Quaterniond::Identity(), Eigen::Vector3d(1, 0, 0));
  const Link odometry_a = MakeLink(1, 2, LinkType::kOdometry, step, Information6d::Identity());
  const Link odometry_b = MakeLink(3, 4, LinkType::kOdometry, step, Information6d::Identity());
  graph.AddLink(odometry_a);
  graph.AddLink(odometry_b);
  EXPECT_FALSE(LinksJoinComponents(graph, {}));
  const Link across = MakeLink(4, 2, LinkType::kLoopClosure, step, Information6d::Identity());
  graph.AddLink(across);
  EXPECT_TRUE(LinksJoinComponents(graph, {KeyOf(across)}));
  // Once joined, a second link between the sessions joins nothing.
  const Link again = MakeLink(3, 1, LinkType::kProximity, step, Information6d::Identity());
  graph.AddLink(again);
  EXPECT_FALSE(LinksJoinComponents(graph, {KeyOf(again)}));
  // Added together, the two links do join the sessions.
  EXPECT_TRUE(LinksJoinComponents(graph, {KeyOf(across), KeyOf(again)}));
  // Within one session nothing is joined.
  const Link inside = MakeLink(2, 1, LinkType::kLoopClosure, step, Information6d::Identity());
  graph.AddLink(inside);
  EXPECT_FALSE(LinksJoinComponents(graph, {KeyOf(inside)}));
}

// The reference's rule (spec 7.3.4): poses start from the current ones unless
// a link added this step joins two components. A within-session closure then
// keeps the current poses as the starting point, a join re-initialises.
TEST(OptimizePoseGraph, InitializesFromLinksOnlyWhenComponentsJoin) {
  OdometryModel exact;
  exact.yaw_bias_rad = exact.noise_m = exact.noise_rad = 0.0;
  PoseGraphOptimizerOptions options;
  options.initialization = PoseInitialization::kWhenComponentsJoin;

  PoseGraph graph;
  const std::vector<Rigid3d> truth0 = AddDriftingLoop(&graph, 1, 0, Rigid3d(), 2, exact);
  const Rigid3d odom1_from_world(Eigen::Quaterniond(Eigen::AngleAxisd(2.0, Eigen::Vector3d::UnitZ())),
                                 Eigen::Vector3d(10.0, -4.0, 1.0));
  const NodeId first1 = 101;
  const std::vector<Rigid3d> truth1 = AddDriftingLoop(&graph, first1, 1, odom1_from_world, 3, exact);

  // A closure within session 0, on a graph whose poses were moved off the
  // links: the solver starts from the moved poses.
  graph.SetPose(20, Rigid3d(truth0[19].rotation, truth0[19].translation + Eigen::Vector3d(0, 0, 0.3)));
  const Link inside = MakeLink(kLoopNodes, 1, LinkType::kLoopClosure,
                               truth0[kLoopNodes - 1].Inverse() * truth0[0],
                               DiagonalInformation(0.01, 0.005));
  graph.AddLink(inside);
  PoseGraph every = graph;
  OptimizationSummary summary = OptimizePoseGraph(options, {KeyOf(inside)}, &graph);
  ASSERT_TRUE(summary.accepted());
  EXPECT_FALSE(summary.reinitialized);
  EXPECT_GT(summary.initial_cost, 1.0);  // the moved pose costs until solved
  PoseGraphOptimizerOptions always;
  always.initialization = PoseInitialization::kEveryOptimization;
  const OptimizationSummary every_summary = OptimizePoseGraph(always, {KeyOf(inside)}, &every);
  EXPECT_TRUE(every_summary.reinitialized);
  EXPECT_LT(every_summary.initial_cost, 1e-12);  // exact links: re-initialised poses cost nothing
  EXPECT_LT(MeanPositionError(graph, truth0, 1), 1e-3);

  // A closure from session 1 to session 0 joins them: re-initialised, and
  // session 1 lands in session 0's frame.
  const Link across = MakeLink(first1 + 9, 10, LinkType::kLoopClosure,
                               truth1[9].Inverse() * truth0[9], DiagonalInformation(0.01, 0.005));
  graph.AddLink(across);
  summary = OptimizePoseGraph(options, {KeyOf(across)}, &graph);
  ASSERT_TRUE(summary.accepted());
  EXPECT_TRUE(summary.reinitialized);
  EXPECT_LT(MeanPositionError(graph, truth1, first1), 1e-3);

  options.initialization = PoseInitialization::kNever;
  EXPECT_FALSE(OptimizePoseGraph(options, {}, &graph).reinitialized);
}

}  // namespace
}  // namespace duskmap
