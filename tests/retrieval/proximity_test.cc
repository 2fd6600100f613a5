#include "slam/retrieval/proximity.h"

#include <cmath>

#include <gtest/gtest.h>

#include "slam/core/check.h"

namespace duskmap {
namespace {

Rigid3d At(double x, double y, double yaw_rad = 0.0) {
  // Camera z forward, rotated about the world's vertical (camera y) axis.
  return Rigid3d(Eigen::Quaterniond(Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitY())),
                 Eigen::Vector3d(x, y, 0.0));
}

// Three sessions pass the same spot: nodes 1-3 (session 0), 11-13, 21-23.
struct Scene {
  PlaceGraph graph{16};
  std::vector<ProximityNode> nodes;
  Scene() {
    for (int s = 0; s < 3; ++s) {
      for (int i = 1; i <= 3; ++i) {
        const NodeId id = 10 * s + i;
        graph.AddNode(id, s);
        if (i > 1) graph.AddLink(id - 1, id, LinkType::kOdometry);
        // All sessions' middle nodes lie 0.5 m from the origin.
        const double angle = 2.0 * M_PI * s / 3.0;
        const double offset = 0.3 * (i - 2);
        nodes.push_back({id, At(0.5 * std::cos(angle) + offset, 0.5 * std::sin(angle))});
      }
    }
  }
};

TEST(Proximity, PrefersTheVisuallyMostSimilarAmongEquidistantNodes) {
  Scene scene;
  ProximityOptions options;
  const auto likelihood = [](NodeId n) { return n == 22 ? 3.0f : (n == 2 ? 1.5f : 1.0f); };
  const ProximityResult r =
      FindProximityCandidates(options, At(0, 0), scene.nodes, scene.graph, likelihood);
  EXPECT_EQ(r.num_paths, 3);
  ASSERT_EQ(r.candidates.size(), 3u);
  EXPECT_EQ(r.candidates[0].node, 22);
  EXPECT_EQ(r.candidates[1].node, 2);
  EXPECT_EQ(r.candidates[0].path, (std::vector<NodeId>{21, 22, 23}));
  EXPECT_NEAR(r.candidates[0].distance_m, 0.5, 1e-9);
  // Localization uses one path: only the most similar.
  options.max_paths = 1;
  const ProximityResult one =
      FindProximityCandidates(options, At(0, 0), scene.nodes, scene.graph, likelihood);
  ASSERT_EQ(one.candidates.size(), 1u);
  EXPECT_EQ(one.candidates[0].node, 22);
}

TEST(Proximity, WithoutLikelihoodTheNearestWinsAndFiltersApply) {
  Scene scene;
  ProximityOptions options;
  const auto none = [](NodeId) { return 0.0f; };
  const ProximityResult r =
      FindProximityCandidates(options, At(0.45, 0.0), scene.nodes, scene.graph, none);
  ASSERT_FALSE(r.candidates.empty());
  EXPECT_EQ(r.candidates[0].node, 2);  // (0.5, 0) is 0.05 m away
  // Already linked nodes are skipped; a path falls back to its nearest other node.
  const ProximityResult linked = FindProximityCandidates(
      options, At(0.45, 0.0), scene.nodes, scene.graph, none, [](NodeId n) { return n == 2; });
  EXPECT_EQ(linked.num_skipped, 1);
  for (const auto& c : linked.candidates) EXPECT_NE(c.node, 2);
  // Facing the other way: nothing in the 45 degree window.
  const ProximityResult behind =
      FindProximityCandidates(options, At(0, 0, M_PI), scene.nodes, scene.graph, none);
  EXPECT_TRUE(behind.candidates.empty());
  EXPECT_EQ(behind.num_in_radius, 9);
  // Far away: nothing within the 1 m radius.
  EXPECT_EQ(FindProximityCandidates(options, At(5, 5), scene.nodes, scene.graph, none).num_in_radius, 0);
  options.local_radius_m = 0.0;
  EXPECT_THROW(FindProximityCandidates(options, At(0, 0), scene.nodes, scene.graph, none), ConfigError);
}

// Each of the reference's conditions (spec §5) refuses a candidate on its own:
// a single node 0.5 m ahead is proposed; moved out of the radius, turned past
// the heading window, beyond the path filtering radius, in a path past the
// path limit, or already linked, it is not.
TEST(Proximity, EachConditionRefusesACandidateOnItsOwn) {
  PlaceGraph graph{16};
  for (NodeId id : {1, 2}) graph.AddNode(id, static_cast<SessionId>(id));
  const auto none = [](NodeId) { return 0.0f; };
  ProximityOptions options;
  const auto candidates = [&](const std::vector<ProximityNode>& nodes,
                              const std::function<bool(NodeId)>& linked = {}) {
    return FindProximityCandidates(options, At(0, 0), nodes, graph, none, linked).candidates;
  };
  const ProximityNode ahead{1, At(0.5, 0.0)};
  ASSERT_EQ(candidates({ahead}).size(), 1u);
  EXPECT_EQ(candidates({ahead})[0].node, 1);
  EXPECT_TRUE(candidates({{1, At(1.2, 0.0)}}).empty());                 // radius 1 m
  EXPECT_TRUE(candidates({{1, At(0.5, 0.0, 50.0 * M_PI / 180.0)}}).empty());  // angle 45 deg
  EXPECT_EQ(candidates({{1, At(0.5, 0.0, 40.0 * M_PI / 180.0)}}).size(), 1u);
  EXPECT_TRUE(candidates({ahead}, [](NodeId n) { return n == 1; }).empty());  // linked
  options.path_filtering_radius_m = 0.4;                                 // target too far
  EXPECT_TRUE(candidates({ahead}).empty());
  options.path_filtering_radius_m = 1.0;
  // Two paths (two sessions, no odometry link between them): the paper's
  // localization runs try one, the nearer without likelihoods.
  options.max_paths = 1;
  const std::vector<ProximityCandidate> one = candidates({ahead, {2, At(0.3, 0.0)}});
  ASSERT_EQ(one.size(), 1u);
  EXPECT_EQ(one[0].node, 2);
  options.max_paths = 0;
  EXPECT_EQ(candidates({ahead, {2, At(0.3, 0.0)}}).size(), 2u);
}

}  // namespace
}  // namespace duskmap
