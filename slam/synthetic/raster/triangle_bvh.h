// A bounding-volume hierarchy over world-space triangles, for the rays the
// furniture meshes take part in: nearest hits and shadow (any-hit) queries.
// Triangles are stored as float (metres; a 10 m apartment keeps about a
// micrometre), rays and the intersection arithmetic are double. The build
// splits nodes by the binned surface-area heuristic (SAH) and is
// deterministic (same triangles and options, same tree); queries are const
// and single-threaded.
//
// Ray/triangle test: Moller and Trumbore, "Fast, minimum storage
// ray/triangle intersection" (1997), in double, without culling (both sides
// of a triangle are hit, as a shadow needs). A ray parallel to the plane
// (|det| <= 1e-12 |e1 x e2| |dir|) misses; barycentrics may fall short of
// [0, 1] by 1e-9 so that a ray through the shared edge of two triangles
// hits at least one of them.
#pragma once

#include <array>
#include <optional>
#include <vector>

#include <Eigen/Core>

namespace duskmap {

struct TriangleBvhOptions {
  int max_leaf_triangles = 4;   // a node with at most this many triangles is a leaf
  int sah_bins = 16;            // centroid bins per axis for the SAH split
  // Hits nearer than this to the ray origin are ignored (metres): what keeps
  // a shadow ray from hitting the surface it leaves (lighting.cc uses 1e-4).
  double min_distance_m = 1e-4;

  void Check() const;  // throws ConfigError naming the field
};

using WorldTriangle = std::array<Eigen::Vector3f, 3>;

struct TriangleHit {
  int triangle = -1;        // index into the triangles the BVH was built from
  double distance_m = 0.0;  // along the ray (in units of its direction's length)
  double b1 = 0.0;          // barycentrics of the hit: b0 v0 + b1 v1 + b2 v2,
  double b2 = 0.0;          // b0 = 1 - b1 - b2
};

// The Moller-Trumbore test of one triangle: the hit at distance in
// (min_distance, max_distance), or nullopt. The BVH's queries use it.
std::optional<TriangleHit> IntersectTriangle(const WorldTriangle& triangle, const Eigen::Vector3d& origin,
                                             const Eigen::Vector3d& direction, double min_distance,
                                             double max_distance);

class TriangleBvh {
 public:
  TriangleBvh() = default;  // empty: no query hits
  // Builds over `triangles` (their indices are the hits' triangle ids).
  // Degenerate (zero-area) triangles are left out: they are never hit.
  // Throws ConfigError for invalid options and InputError for a triangle
  // with a non-finite vertex.
  explicit TriangleBvh(const std::vector<WorldTriangle>& triangles,
                       const TriangleBvhOptions& options = TriangleBvhOptions());

  // The nearest hit along the ray at distance in (min_distance_m,
  // max_distance) (ties: the lower triangle index), or nullopt.
  std::optional<TriangleHit> Intersect(const Eigen::Vector3d& origin, const Eigen::Vector3d& unit_direction,
                                       double max_distance) const;
  // Whether any triangle is hit at distance in (min_distance_m,
  // max_distance); stops at the first hit found.
  bool Occluded(const Eigen::Vector3d& origin, const Eigen::Vector3d& unit_direction,
                double max_distance) const;

  bool empty() const { return nodes_.empty(); }
  int num_triangles() const { return static_cast<int>(triangles_.size()); }  // non-degenerate ones
  int num_nodes() const { return static_cast<int>(nodes_.size()); }

 private:
  // Depth-first layout: an inner node's first child follows it, its second
  // child is at `second_child`; a leaf holds triangles_[first, first + count).
  struct Node {
    float box_min[3];
    float box_max[3];
    int first_or_second_child = 0;
    int count = 0;  // 0 for an inner node
  };
  template <bool kAnyHit>
  std::optional<TriangleHit> Traverse(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                                      double max_distance) const;
  // Builds the nodes, reordering `order` (input indices) into leaf order.
  void Build(std::vector<int>* order, const std::vector<WorldTriangle>& input);

  TriangleBvhOptions options_;
  std::vector<Node> nodes_;
  std::vector<WorldTriangle> triangles_;  // in leaf order
  std::vector<int> ids_;                  // input index of each of triangles_
};

}  // namespace duskmap
