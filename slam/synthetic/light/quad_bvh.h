// A bounding-volume hierarchy over some of a scene's quads, for the shadow
// rays of the light maps: whether any of them lies on a segment. The leaves
// test each quad with Quad::Intersect, so a query answers exactly what a
// loop over the same quads answers (same predicate, same arithmetic); the
// tree only skips quads whose padded bounding box the segment misses.
// Median split on the longest axis of the centroids, deterministic; queries
// are const and single-threaded.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "slam/synthetic/scene/scene.h"

namespace duskmap {

class QuadBvh {
 public:
  QuadBvh() = default;  // empty: no query hits
  // Builds over quads[i] for i in `indices` (each in range). The BVH keeps a
  // pointer to `quads`, which must outlive it unchanged.
  QuadBvh(const std::vector<Quad>& quads, const std::vector<int>& indices);

  // Whether a quad other than `skip_quad` is hit at a distance in
  // (min_distance_m, max_distance) along the unit `direction` from `origin`.
  bool Occluded(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double max_distance,
                int skip_quad, double min_distance_m) const;

  int num_quads() const { return static_cast<int>(ids_.size()); }
  int num_nodes() const { return static_cast<int>(nodes_.size()); }

 private:
  // Depth-first layout: an inner node's first child follows it, its second
  // child is at `first_or_second`; a leaf holds ids_[first, first + count).
  struct Node {
    Eigen::Vector3d box_min = Eigen::Vector3d::Zero();
    Eigen::Vector3d box_max = Eigen::Vector3d::Zero();
    int first_or_second = 0;
    int count = 0;  // 0 for an inner node
  };
  // A quad while building: its scene index and its centre.
  struct BuildEntry {
    int id = -1;
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  };
  // Builds the node over entries[first, first + count), partitioning them
  // in place, and returns its index.
  int Build(int first, int count, std::vector<BuildEntry>* entries);

  const std::vector<Quad>* quads_ = nullptr;
  std::vector<Node> nodes_;
  std::vector<int> ids_;  // scene quad indices, in leaf order
};

}  // namespace duskmap
