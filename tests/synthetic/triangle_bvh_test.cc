#include "slam/synthetic/raster/triangle_bvh.h"

#include <cmath>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "slam/core/check.h"

namespace duskmap {
namespace {

// Small random triangles in a 10 m cube.
std::vector<WorldTriangle> RandomTriangles(int count, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> position(-5.0f, 5.0f), offset(-0.4f, 0.4f);
  std::vector<WorldTriangle> triangles(static_cast<size_t>(count));
  for (WorldTriangle& t : triangles) {
    const Eigen::Vector3f c(position(rng), position(rng), position(rng));
    for (Eigen::Vector3f& v : t) v = c + Eigen::Vector3f(offset(rng), offset(rng), offset(rng));
  }
  return triangles;
}

struct TestRay {
  Eigen::Vector3d origin;
  Eigen::Vector3d direction;  // unit
  double max_distance;
};

std::vector<TestRay> RandomRays(int count, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> position(-7.0, 7.0), normal(-1.0, 1.0), length(0.5, 15.0);
  std::vector<TestRay> rays;
  while (static_cast<int>(rays.size()) < count) {
    const Eigen::Vector3d d(normal(rng), normal(rng), normal(rng));
    if (d.norm() < 0.1 || d.norm() > 1.0) continue;
    rays.push_back({Eigen::Vector3d(position(rng), position(rng), position(rng)), d.normalized(), length(rng)});
  }
  return rays;
}

// Every triangle tested, nearest first, ties to the lower index.
std::optional<TriangleHit> BruteForce(const std::vector<WorldTriangle>& triangles, const TestRay& ray,
                                      double min_distance) {
  std::optional<TriangleHit> best;
  for (size_t i = 0; i < triangles.size(); ++i) {
    std::optional<TriangleHit> hit =
        IntersectTriangle(triangles[i], ray.origin, ray.direction, min_distance, ray.max_distance);
    if (hit && (!best || hit->distance_m < best->distance_m)) {
      best = hit;
      best->triangle = static_cast<int>(i);
    }
  }
  return best;
}

TEST(TriangleBvh, NearestHitsMatchBruteForce) {
  const std::vector<WorldTriangle> triangles = RandomTriangles(4000, 1);
  const TriangleBvh bvh(triangles);
  EXPECT_EQ(bvh.num_triangles(), 4000);
  int hits = 0;
  for (const TestRay& ray : RandomRays(3000, 2)) {
    const std::optional<TriangleHit> expected = BruteForce(triangles, ray, TriangleBvhOptions().min_distance_m);
    const std::optional<TriangleHit> actual = bvh.Intersect(ray.origin, ray.direction, ray.max_distance);
    ASSERT_EQ(actual.has_value(), expected.has_value());
    if (!expected) continue;
    ++hits;
    EXPECT_EQ(actual->triangle, expected->triangle);
    EXPECT_EQ(actual->distance_m, expected->distance_m);
    EXPECT_EQ(actual->b1, expected->b1);
    EXPECT_EQ(actual->b2, expected->b2);
    const WorldTriangle& t = triangles[static_cast<size_t>(actual->triangle)];
    const Eigen::Vector3d on_triangle = (1.0 - actual->b1 - actual->b2) * t[0].cast<double>() +
                                        actual->b1 * t[1].cast<double>() + actual->b2 * t[2].cast<double>();
    EXPECT_NEAR((on_triangle - (ray.origin + actual->distance_m * ray.direction)).norm(), 0.0, 1e-9);
  }
  EXPECT_GT(hits, 500);
}

TEST(TriangleBvh, OcclusionMatchesBruteForce) {
  const std::vector<WorldTriangle> triangles = RandomTriangles(3000, 3);
  TriangleBvhOptions options;
  options.max_leaf_triangles = 2;
  options.sah_bins = 8;
  const TriangleBvh bvh(triangles, options);
  int occluded = 0, total = 0;
  for (const TestRay& ray : RandomRays(3000, 4)) {
    const bool expected = BruteForce(triangles, ray, options.min_distance_m).has_value();
    EXPECT_EQ(bvh.Occluded(ray.origin, ray.direction, ray.max_distance), expected);
    occluded += expected;
    ++total;
  }
  EXPECT_GT(occluded, 300);
  EXPECT_LT(occluded, total - 300);
}

TEST(TriangleBvh, EmptyHitsNothing) {
  const Eigen::Vector3d origin(0, 0, 0), direction(0, 0, 1);
  const TriangleBvh none;
  EXPECT_TRUE(none.empty());
  EXPECT_FALSE(none.Intersect(origin, direction, 100.0).has_value());
  EXPECT_FALSE(none.Occluded(origin, direction, 100.0));
  const TriangleBvh from_empty{std::vector<WorldTriangle>()};
  EXPECT_TRUE(from_empty.empty());
  EXPECT_FALSE(from_empty.Occluded(origin, direction, 100.0));
}

TEST(TriangleBvh, DegenerateTrianglesAreIgnored) {
  // A segment (zero area) and a repeated vertex across the ray, then a real
  // triangle behind them: only the real one (input index 2) is hit.
  const std::vector<WorldTriangle> triangles = {
      {Eigen::Vector3f(-1, 0, 1), Eigen::Vector3f(0, 0, 1), Eigen::Vector3f(1, 0, 1)},
      {Eigen::Vector3f(-1, -1, 2), Eigen::Vector3f(-1, -1, 2), Eigen::Vector3f(1, 1, 2)},
      {Eigen::Vector3f(-1, -1, 3), Eigen::Vector3f(1, -1, 3), Eigen::Vector3f(0, 1, 3)},
  };
  const TriangleBvh bvh(triangles);
  EXPECT_EQ(bvh.num_triangles(), 1);
  const std::optional<TriangleHit> hit = bvh.Intersect(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0, 0, 1), 10.0);
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->triangle, 2);
  EXPECT_NEAR(hit->distance_m, 3.0, 1e-12);
  const TriangleBvh only_degenerate(std::vector<WorldTriangle>(triangles.begin(), triangles.begin() + 2));
  EXPECT_TRUE(only_degenerate.empty());
  EXPECT_FALSE(only_degenerate.Occluded(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0, 0, 1), 10.0));
}

TEST(TriangleBvh, HitsBothSidesWithinTheDistanceRange) {
  const std::vector<WorldTriangle> triangles = {
      {Eigen::Vector3f(-1, -1, 0), Eigen::Vector3f(1, -1, 0), Eigen::Vector3f(0, 1, 0)}};
  const TriangleBvh bvh(triangles);
  EXPECT_TRUE(bvh.Occluded(Eigen::Vector3d(0, 0, 2), Eigen::Vector3d(0, 0, -1), 3.0));
  EXPECT_TRUE(bvh.Occluded(Eigen::Vector3d(0, 0, -2), Eigen::Vector3d(0, 0, 1), 3.0));
  EXPECT_FALSE(bvh.Occluded(Eigen::Vector3d(0, 0, -2), Eigen::Vector3d(0, 0, 1), 1.9));  // stops short
  EXPECT_FALSE(bvh.Occluded(Eigen::Vector3d(0, 0, -2), Eigen::Vector3d(0, 0, -1), 10.0));  // facing away
  // A shadow ray leaving the surface does not hit it (min_distance_m).
  EXPECT_FALSE(bvh.Occluded(Eigen::Vector3d(0.1, 0.1, 0), Eigen::Vector3d(0, 0.6, 0.8), 10.0));
  EXPECT_FALSE(bvh.Intersect(Eigen::Vector3d(0.1, 0.1, 1e-6), Eigen::Vector3d(0, 0, -1), 10.0).has_value());
  // Parallel to the plane: no hit.
  EXPECT_FALSE(bvh.Occluded(Eigen::Vector3d(-3, 0, 0), Eigen::Vector3d(1, 0, 0), 10.0));
}

TEST(TriangleBvh, ARayThroughASharedEdgeHitsTheSurface) {
  // A unit square of two triangles; rays exactly through the diagonal.
  const Eigen::Vector3f a(0, 0, 0), b(1, 0, 0), c(1, 1, 0), d(0, 1, 0);
  const std::vector<WorldTriangle> triangles = {{a, b, c}, {a, c, d}};
  const TriangleBvh bvh(triangles);
  for (int i = 1; i < 100; ++i) {
    const double s = i / 100.0;
    const std::optional<TriangleHit> hit = bvh.Intersect(Eigen::Vector3d(s, s, 1), Eigen::Vector3d(0, 0, -1), 2.0);
    ASSERT_TRUE(hit.has_value()) << s;
    EXPECT_EQ(hit->triangle, 0);  // both hit at the same distance: the lower index
    EXPECT_NEAR(hit->distance_m, 1.0, 1e-12);
  }
}

TEST(TriangleBvh, BuildsTheSameTreeEveryTime) {
  const std::vector<WorldTriangle> triangles = RandomTriangles(2000, 5);
  const TriangleBvh first(triangles), second(triangles);
  EXPECT_EQ(first.num_nodes(), second.num_nodes());
  for (const TestRay& ray : RandomRays(300, 6)) {
    const std::optional<TriangleHit> h1 = first.Intersect(ray.origin, ray.direction, ray.max_distance);
    const std::optional<TriangleHit> h2 = second.Intersect(ray.origin, ray.direction, ray.max_distance);
    ASSERT_EQ(h1.has_value(), h2.has_value());
    if (h1) {
      EXPECT_EQ(h1->triangle, h2->triangle);
    }
  }
}

TEST(TriangleBvh, ManyCoincidentTrianglesStillBuildAShallowTree) {
  // Identical centroids (no SAH split separates them): median splits.
  const WorldTriangle t = {Eigen::Vector3f(-1, -1, 1), Eigen::Vector3f(1, -1, 1), Eigen::Vector3f(0, 1, 1)};
  const TriangleBvh bvh(std::vector<WorldTriangle>(1000, t));
  const std::optional<TriangleHit> hit = bvh.Intersect(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0, 0, 1), 5.0);
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->triangle, 0);
  EXPECT_LT(bvh.num_nodes(), 1000);
}

TEST(TriangleBvh, RejectsInvalidOptionsAndNonFiniteVertices) {
  TriangleBvhOptions options;
  options.max_leaf_triangles = 0;
  EXPECT_THROW(options.Check(), ConfigError);
  options = TriangleBvhOptions();
  options.sah_bins = 1;
  EXPECT_THROW(options.Check(), ConfigError);
  options = TriangleBvhOptions();
  options.min_distance_m = -1.0;
  EXPECT_THROW(TriangleBvh(RandomTriangles(3, 1), options), ConfigError);
  std::vector<WorldTriangle> triangles = RandomTriangles(3, 1);
  triangles[1][2].y() = std::numeric_limits<float>::quiet_NaN();
  EXPECT_THROW(TriangleBvh{triangles}, InputError);
}

}  // namespace
}  // namespace duskmap
