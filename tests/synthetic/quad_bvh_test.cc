#include "slam/synthetic/light/quad_bvh.h"

#include <random>

#include <gtest/gtest.h>

namespace duskmap {
namespace {

Quad MakeQuad(const Eigen::Vector3d& origin, const Eigen::Vector3d& u, const Eigen::Vector3d& v, double size_u_m,
              double size_v_m) {
  Quad q;
  q.origin_in_world = origin;
  q.u_axis = u;
  q.v_axis = v;
  q.size_u_m = size_u_m;
  q.size_v_m = size_v_m;
  return q;
}

// A room of axis-aligned walls, floor and ceiling (as the apartment's quads
// are), with axis-aligned and tilted quads inside.
std::vector<Quad> RandomQuads(int count, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> position(0.0, 5.0), size(0.05, 1.5), unit(-1.0, 1.0);
  std::uniform_int_distribution<int> kind(0, 3);
  std::vector<Quad> quads;
  const Eigen::Vector3d x = Eigen::Vector3d::UnitX(), y = Eigen::Vector3d::UnitY(), z = Eigen::Vector3d::UnitZ();
  quads.push_back(MakeQuad({0, 0, 0}, x, y, 5.0, 5.0));    // floor
  quads.push_back(MakeQuad({0, 5, 2.5}, x, -y, 5.0, 5.0));  // ceiling
  quads.push_back(MakeQuad({0, 0, 2.5}, x, -z, 5.0, 2.5));  // a wall
  while (static_cast<int>(quads.size()) < count) {
    const Eigen::Vector3d origin(position(rng), position(rng), 0.5 * position(rng));
    switch (kind(rng)) {
      case 0: quads.push_back(MakeQuad(origin, x, y, size(rng), size(rng))); break;   // a table top
      case 1: quads.push_back(MakeQuad(origin, x, -z, size(rng), size(rng))); break;  // a cabinet front
      case 2: quads.push_back(MakeQuad(origin, -y, -z, size(rng), size(rng))); break;
      default: {
        const Eigen::Vector3d u = Eigen::Vector3d(unit(rng), unit(rng), unit(rng)).normalized();
        const Eigen::Vector3d v = u.cross(Eigen::Vector3d(unit(rng), unit(rng), unit(rng))).normalized();
        quads.push_back(MakeQuad(origin, u, v, size(rng), size(rng)));
      }
    }
  }
  return quads;
}

bool BruteForce(const std::vector<Quad>& quads, const std::vector<int>& indices, const Eigen::Vector3d& origin,
                const Eigen::Vector3d& direction, double max_distance, int skip, double min_distance) {
  for (const int i : indices) {
    if (i == skip) continue;
    const double d = quads[static_cast<size_t>(i)].Intersect(origin, direction);
    if (d > min_distance && d < max_distance) return true;
  }
  return false;
}

TEST(QuadBvh, AnswersAsTheLoopOverItsQuadsDoes) {
  const std::vector<Quad> quads = RandomQuads(300, 7);
  // Every quad but a few, so that quads outside the BVH are never hit.
  std::vector<int> indices;
  for (int i = 0; i < static_cast<int>(quads.size()); ++i) {
    if (i % 10 != 3) indices.push_back(i);
  }
  const QuadBvh bvh(quads, indices);
  EXPECT_EQ(bvh.num_quads(), static_cast<int>(indices.size()));
  EXPECT_GT(bvh.num_nodes(), static_cast<int>(indices.size()) / 4);

  std::mt19937 rng(11);
  std::uniform_real_distribution<double> position(0.0, 5.0), unit(-1.0, 1.0), length(0.01, 8.0);
  std::uniform_int_distribution<int> axis(0, 5), pick(0, static_cast<int>(quads.size()) - 1);
  int hits = 0, rays = 0;
  for (int k = 0; k < 20000; ++k) {
    Eigen::Vector3d direction;
    if (k % 4 == 0) {  // along an axis: the slab test's zero components
      direction = Eigen::Vector3d::Zero();
      const int a = axis(rng);
      direction[a % 3] = a < 3 ? 1.0 : -1.0;
    } else {
      direction = Eigen::Vector3d(unit(rng), unit(rng), unit(rng));
      if (direction.norm() < 0.1) continue;
      direction.normalize();
    }
    // Half the rays leave a quad's surface, as a light map's do.
    Eigen::Vector3d origin(position(rng), position(rng), 0.5 * position(rng));
    int skip = -1;
    if (k % 2 == 1) {
      skip = pick(rng);
      const Quad& q = quads[static_cast<size_t>(skip)];
      origin = q.PointAt(0.5 * q.size_u_m, 0.3 * q.size_v_m) + 1e-3 * q.normal();
    }
    const double max_distance = length(rng);
    const bool expected = BruteForce(quads, indices, origin, direction, max_distance, skip, 1e-4);
    EXPECT_EQ(bvh.Occluded(origin, direction, max_distance, skip, 1e-4), expected) << "ray " << k;
    hits += expected;
    ++rays;
  }
  // Both answers occur often, so the comparison means something.
  EXPECT_GT(hits, rays / 10);
  EXPECT_LT(hits, rays * 9 / 10);
}

TEST(QuadBvh, HitsAFlatQuadFromStraightAboveAndAtItsEdge) {
  std::vector<Quad> quads = {MakeQuad({1, 1, 0.7}, Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(), 0.5, 0.5)};
  for (int i = 0; i < 20; ++i) {  // enough quads for inner nodes
    quads.push_back(MakeQuad({3.0 + 0.1 * i, 0, 0}, Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitZ(), 0.05, 0.05));
  }
  std::vector<int> all(quads.size());
  for (size_t i = 0; i < all.size(); ++i) all[i] = static_cast<int>(i);
  const QuadBvh bvh(quads, all);
  const Eigen::Vector3d down = -Eigen::Vector3d::UnitZ();
  EXPECT_TRUE(bvh.Occluded({1.25, 1.25, 2.0}, down, 2.0, -1, 1e-4));
  EXPECT_TRUE(bvh.Occluded({1.5, 1.5, 2.0}, down, 2.0, -1, 1e-4));   // the corner itself
  EXPECT_FALSE(bvh.Occluded({1.5001, 1.25, 2.0}, down, 2.0, -1, 1e-4));
  EXPECT_FALSE(bvh.Occluded({1.25, 1.25, 2.0}, down, 1.2, -1, 1e-4));  // stops short of it
  EXPECT_FALSE(bvh.Occluded({1.25, 1.25, 2.0}, down, 2.0, 0, 1e-4));   // the receiver itself
  EXPECT_FALSE(bvh.Occluded({1.25, 1.25, 0.70005}, down, 2.0, -1, 1e-4));  // nearer than the minimum
}

TEST(QuadBvh, EmptyHitsNothing) {
  const std::vector<Quad> quads = RandomQuads(10, 3);
  EXPECT_FALSE(QuadBvh().Occluded({1, 1, 1}, Eigen::Vector3d::UnitX(), 100.0, -1, 0.0));
  EXPECT_FALSE(QuadBvh(quads, {}).Occluded({0.5, 0.5, 1}, -Eigen::Vector3d::UnitZ(), 100.0, -1, 0.0));
}

}  // namespace
}  // namespace duskmap
