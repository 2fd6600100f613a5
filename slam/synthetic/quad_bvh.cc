#include "slam/synthetic/quad_bvh.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

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

QuadBvh::QuadBvh(const std::vector<Quad>& quads, const std::vector<int>& indices)
    : quads_(&quads), ids_(indices) {
  for (const int i : ids_) {
    SLAM_CHECK_MSG(i >= 0 && i < static_cast<int>(quads.size()), "QuadBvh: quad index out of range");
  }
  if (ids_.empty()) return;
  std::vector<Eigen::Vector3d> centroids(ids_.size());
  for (size_t k = 0; k < ids_.size(); ++k) {
    const Quad& q = quads[static_cast<size_t>(ids_[k])];
    centroids[k] = q.PointAt(0.5 * q.size_u_m, 0.5 * q.size_v_m);
  }
  nodes_.reserve(2 * ids_.size());
  Build(0, static_cast<int>(ids_.size()), &centroids);
}

int QuadBvh::Build(int first, int count, std::vector<Eigen::Vector3d>* centroids) {
  const int index = static_cast<int>(nodes_.size());
  nodes_.push_back(Node());
  Eigen::Vector3d box_min = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d box_max = -box_min;
  Eigen::Vector3d centre_min = box_min, centre_max = box_max;
  for (int k = first; k < first + count; ++k) {
    const Quad& q = (*quads_)[static_cast<size_t>(ids_[static_cast<size_t>(k)])];
    for (const double s : {0.0, q.size_u_m}) {
      for (const double t : {0.0, q.size_v_m}) {
        const Eigen::Vector3d corner = q.PointAt(s, t);
        box_min = box_min.cwiseMin(corner);
        box_max = box_max.cwiseMax(corner);
      }
    }
    centre_min = centre_min.cwiseMin((*centroids)[static_cast<size_t>(k)]);
    centre_max = centre_max.cwiseMax((*centroids)[static_cast<size_t>(k)]);
  }
  nodes_[static_cast<size_t>(index)].box_min = box_min.array() - kPadM;
  nodes_[static_cast<size_t>(index)].box_max = box_max.array() + kPadM;
  int axis = 0;
  (centre_max - centre_min).maxCoeff(&axis);
  if (count <= kMaxLeafQuads || centre_max[axis] <= centre_min[axis]) {
    nodes_[static_cast<size_t>(index)].first_or_second = first;
    nodes_[static_cast<size_t>(index)].count = count;
    return index;
  }
  // Median split along the axis; ties broken by the quad index, so the tree
  // does not depend on the sort's implementation.
  std::vector<int> order(static_cast<size_t>(count));
  std::iota(order.begin(), order.end(), first);
  const int half = count / 2;
  std::nth_element(order.begin(), order.begin() + half, order.end(), [&](int a, int b) {
    const double ca = (*centroids)[static_cast<size_t>(a)][axis], cb = (*centroids)[static_cast<size_t>(b)][axis];
    return ca < cb || (ca == cb && ids_[static_cast<size_t>(a)] < ids_[static_cast<size_t>(b)]);
  });
  std::vector<int> ids(static_cast<size_t>(count));
  std::vector<Eigen::Vector3d> centres(static_cast<size_t>(count));
  for (int k = 0; k < count; ++k) {
    ids[static_cast<size_t>(k)] = ids_[static_cast<size_t>(order[static_cast<size_t>(k)])];
    centres[static_cast<size_t>(k)] = (*centroids)[static_cast<size_t>(order[static_cast<size_t>(k)])];
  }
  std::copy(ids.begin(), ids.end(), ids_.begin() + first);
  std::copy(centres.begin(), centres.end(), centroids->begin() + first);
  Build(first, half, centroids);
  const int second = Build(first + half, count - half, centroids);
  nodes_[static_cast<size_t>(index)].first_or_second = second;
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
