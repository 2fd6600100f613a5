#include "slam/synthetic/light/quad_bvh.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "slam/core/check.h"

namespace duskmap {
namespace {

constexpr int kMaxLeafQuads = 4;
constexpr int kStackSize = 64;
// Boxes grow by this much (metres) on every side: a quad is planar, so its
// box is flat along one axis, and a hit that Quad::Intersect accepts must
// never fall outside its box by rounding.
constexpr double kPadM = 1e-6;

}  // namespace

QuadBvh::QuadBvh(const std::vector<Quad>& quads, const std::vector<int>& indices) : quads_(&quads) {
  std::vector<BuildEntry> entries(indices.size());
  for (size_t k = 0; k < indices.size(); ++k) {
    const int i = indices[k];
    SLAM_CHECK_MSG(i >= 0 && i < static_cast<int>(quads.size()), "QuadBvh: quad index out of range");
    const Quad& q = quads[static_cast<size_t>(i)];
    entries[k] = {i, q.PointAt(0.5 * q.size_u_m, 0.5 * q.size_v_m)};
  }
  if (!entries.empty()) {
    nodes_.reserve(2 * entries.size());
    Build(0, static_cast<int>(entries.size()), &entries);
  }
  ids_.reserve(entries.size());
  for (const BuildEntry& e : entries) ids_.push_back(e.id);
}

int QuadBvh::Build(int first, int count, std::vector<BuildEntry>* entries) {
  const int index = static_cast<int>(nodes_.size());
  nodes_.push_back(Node());
  const auto begin = entries->begin() + first, end = begin + count;
  Eigen::Vector3d box_min = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d box_max = -box_min;
  Eigen::Vector3d centre_min = box_min, centre_max = box_max;
  for (auto e = begin; e != end; ++e) {
    const Quad& q = (*quads_)[static_cast<size_t>(e->id)];
    for (const double s : {0.0, q.size_u_m}) {
      for (const double t : {0.0, q.size_v_m}) {
        const Eigen::Vector3d corner = q.PointAt(s, t);
        box_min = box_min.cwiseMin(corner);
        box_max = box_max.cwiseMax(corner);
      }
    }
    centre_min = centre_min.cwiseMin(e->centre);
    centre_max = centre_max.cwiseMax(e->centre);
  }
  Node& node = nodes_[static_cast<size_t>(index)];
  node.box_min = box_min.array() - kPadM;
  node.box_max = box_max.array() + kPadM;
  int axis = 0;
  (centre_max - centre_min).maxCoeff(&axis);
  if (count <= kMaxLeafQuads || centre_max[axis] <= centre_min[axis]) {
    node.first_or_second = first;
    node.count = count;
    return index;
  }
  // Median split along the axis; ties broken by the quad index, so the tree
  // does not depend on the partition's implementation.
  const int half = count / 2;
  std::nth_element(begin, begin + half, end, [axis](const BuildEntry& a, const BuildEntry& b) {
    return a.centre[axis] < b.centre[axis] || (a.centre[axis] == b.centre[axis] && a.id < b.id);
  });
  Build(first, half, entries);
  const int second = Build(first + half, count - half, entries);
  nodes_[static_cast<size_t>(index)].first_or_second = second;  // `node` may have moved
  return index;
}

bool QuadBvh::Occluded(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double max_distance,
                       int skip_quad, double min_distance_m) const {
  if (nodes_.empty()) return false;
  int stack[kStackSize];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[static_cast<size_t>(stack[--top])];
    // Slab test of the segment [0, max_distance] against the padded box.
    double t_near = 0.0, t_far = max_distance;
    bool miss = false;
    for (int a = 0; a < 3 && !miss; ++a) {
      if (direction[a] == 0.0) {
        miss = origin[a] < node.box_min[a] || origin[a] > node.box_max[a];
        continue;
      }
      const double inv = 1.0 / direction[a];
      double t0 = (node.box_min[a] - origin[a]) * inv, t1 = (node.box_max[a] - origin[a]) * inv;
      if (t0 > t1) std::swap(t0, t1);
      t_near = std::max(t_near, t0);
      t_far = std::min(t_far, t1);
      miss = t_near > t_far;
    }
    if (miss) continue;
    if (node.count == 0) {
      SLAM_CHECK_MSG(top + 2 <= kStackSize, "QuadBvh: traversal stack overflow");
      stack[top++] = node.first_or_second;
      stack[top++] = static_cast<int>(&node - nodes_.data()) + 1;
      continue;
    }
    for (int k = node.first_or_second; k < node.first_or_second + node.count; ++k) {
      const int i = ids_[static_cast<size_t>(k)];
      if (i == skip_quad) continue;
      const double d = (*quads_)[static_cast<size_t>(i)].Intersect(origin, direction);
      if (d > min_distance_m && d < max_distance) return true;
    }
  }
  return false;
}

}  // namespace duskmap
