#include "slam/synthetic/raster/triangle_bvh.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Geometry>

#include "slam/core/check.h"

namespace duskmap {

void TriangleBvhOptions::Check() const {
  SLAM_THROW_IF_NOT(ConfigError, max_leaf_triangles >= 1 && max_leaf_triangles <= 64)
      << "triangle_bvh.max_leaf_triangles must be in [1, 64], got " << max_leaf_triangles;
  SLAM_THROW_IF_NOT(ConfigError, sah_bins >= 2 && sah_bins <= 256)
      << "triangle_bvh.sah_bins must be in [2, 256], got " << sah_bins;
  SLAM_THROW_IF_NOT(ConfigError, std::isfinite(min_distance_m) && min_distance_m >= 0.0)
      << "triangle_bvh.min_distance_m must be a finite value >= 0, got " << min_distance_m;
}

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
// How far barycentrics may fall outside [0, 1] (shared edges are hit).
constexpr double kBarycentricSlack = 1e-9;
// A ray whose |cos| with the plane's normal is at most this misses.
constexpr double kParallelCos = 1e-12;
// Below this depth nodes split at the median, which bounds the tree's depth
// (and the traversal stack) whatever the triangles.
constexpr int kMaxSahDepth = 40;
constexpr int kStackSize = 128;

// An axis-aligned box in double while building.
struct Box {
  Eigen::Vector3d min = Eigen::Vector3d::Constant(kInfinity);
  Eigen::Vector3d max = Eigen::Vector3d::Constant(-kInfinity);

  void Grow(const Box& b) {
    min = min.cwiseMin(b.min);
    max = max.cwiseMax(b.max);
  }
  void Grow(const Eigen::Vector3d& p) {
    min = min.cwiseMin(p);
    max = max.cwiseMax(p);
  }
  bool IsEmpty() const { return !(min.x() <= max.x()); }
  double HalfArea() const {
    if (IsEmpty()) return 0.0;
    const Eigen::Vector3d e = max - min;
    return e.x() * e.y() + e.y() * e.z() + e.z() * e.x();
  }
};

Box BoxOf(const WorldTriangle& t) {
  Box b;
  for (const Eigen::Vector3f& v : t) b.Grow(v.cast<double>());
  return b;
}

bool IsDegenerate(const WorldTriangle& t) {
  const Eigen::Vector3d v0 = t[0].cast<double>();
  return (t[1].cast<double>() - v0).cross(t[2].cast<double>() - v0).squaredNorm() == 0.0;
}

float RoundDown(double value) {
  float f = static_cast<float>(value);
  if (f > value) f = std::nextafter(f, -std::numeric_limits<float>::infinity());
  return f;
}

float RoundUp(double value) {
  float f = static_cast<float>(value);
  if (f < value) f = std::nextafter(f, std::numeric_limits<float>::infinity());
  return f;
}

}  // namespace

std::optional<TriangleHit> IntersectTriangle(const WorldTriangle& triangle, const Eigen::Vector3d& origin,
                                             const Eigen::Vector3d& direction, double min_distance,
                                             double max_distance) {
  const Eigen::Vector3d v0 = triangle[0].cast<double>();
  const Eigen::Vector3d e1 = triangle[1].cast<double>() - v0;
  const Eigen::Vector3d e2 = triangle[2].cast<double>() - v0;
  const Eigen::Vector3d p = direction.cross(e2);
  const double det = e1.dot(p);  // = -direction . (e1 x e2)
  const double limit = kParallelCos * kParallelCos * e1.cross(e2).squaredNorm() * direction.squaredNorm();
  if (!(det * det > limit)) return std::nullopt;  // parallel, degenerate or NaN
  const double inv_det = 1.0 / det;
  const Eigen::Vector3d s = origin - v0;
  const double b1 = s.dot(p) * inv_det;
  if (b1 < -kBarycentricSlack || b1 > 1.0 + kBarycentricSlack) return std::nullopt;
  const Eigen::Vector3d q = s.cross(e1);
  const double b2 = direction.dot(q) * inv_det;
  if (b2 < -kBarycentricSlack || b1 + b2 > 1.0 + kBarycentricSlack) return std::nullopt;
  const double t = e2.dot(q) * inv_det;
  if (!(t > min_distance && t < max_distance)) return std::nullopt;
  TriangleHit hit;
  hit.distance_m = t;
  hit.b1 = b1;
  hit.b2 = b2;
  return hit;
}

TriangleBvh::TriangleBvh(const std::vector<WorldTriangle>& triangles, const TriangleBvhOptions& options)
    : options_(options) {
  options_.Check();
  std::vector<int> order;
  order.reserve(triangles.size());
  for (size_t i = 0; i < triangles.size(); ++i) {
    for (const Eigen::Vector3f& v : triangles[i]) {
      SLAM_THROW_IF_NOT(InputError, v.allFinite())
          << "TriangleBvh: triangle " << i << " has a non-finite vertex";
    }
    if (!IsDegenerate(triangles[i])) order.push_back(static_cast<int>(i));
  }
  SLAM_THROW_IF_NOT(InputError, order.size() < static_cast<size_t>(std::numeric_limits<int>::max() / 2))
      << "TriangleBvh: too many triangles (" << order.size() << ")";
  if (order.empty()) return;
  nodes_.reserve(2 * order.size() / static_cast<size_t>(options_.max_leaf_triangles) + 1);
  Build(&order, triangles);
  triangles_.reserve(order.size());
  ids_ = order;
  for (const int i : order) triangles_.push_back(triangles[static_cast<size_t>(i)]);
}

namespace {

struct BuildItem {
  Box box;
  Eigen::Vector3d centroid;
};

// The SAH split of items[begin, end): the axis and the bin the left side
// ends before, or axis -1 when no split separates the centroids.
struct Split {
  int axis = -1;
  int bin = 0;
  double cost = kInfinity;
};

int BinOf(double c, double lo, double scale, int bins) {
  return std::clamp(static_cast<int>((c - lo) * scale), 0, bins - 1);
}

Split FindSahSplit(const std::vector<BuildItem>& items, const std::vector<int>& order, int begin, int end,
                   const Box& centroids, int bins) {
  Split best;
  std::vector<Box> bin_box(static_cast<size_t>(bins));
  std::vector<int> bin_count(static_cast<size_t>(bins));
  std::vector<double> right_cost(static_cast<size_t>(bins));
  for (int axis = 0; axis < 3; ++axis) {
    const double lo = centroids.min[axis], extent = centroids.max[axis] - lo;
    if (!(extent > 0.0)) continue;
    const double scale = bins / extent;
    std::fill(bin_box.begin(), bin_box.end(), Box());
    std::fill(bin_count.begin(), bin_count.end(), 0);
    for (int k = begin; k < end; ++k) {
      const BuildItem& item = items[static_cast<size_t>(order[k])];
      const int b = BinOf(item.centroid[axis], lo, scale, bins);
      bin_box[b].Grow(item.box);
      ++bin_count[b];
    }
    // right_cost[b]: the SAH term of bins [b, bins).
    Box right;
    int right_count = 0;
    for (int b = bins - 1; b >= 1; --b) {
      right.Grow(bin_box[b]);
      right_count += bin_count[b];
      right_cost[b] = right.HalfArea() * right_count;
    }
    Box left;
    int left_count = 0;
    for (int b = 1; b < bins; ++b) {
      left.Grow(bin_box[b - 1]);
      left_count += bin_count[b - 1];
      if (left_count == 0 || left_count == end - begin) continue;
      const double cost = left.HalfArea() * left_count + right_cost[b];
      if (cost < best.cost) best = {axis, b, cost};
    }
  }
  return best;
}

// Splits order[begin, end) in two non-empty parts and returns where the
// second starts: by the SAH split when `use_sah` and one separates the
// centroids, else at the median of the centroids along their longest axis
// (ties by index, so the result is the same on every run).
int SplitRange(const std::vector<BuildItem>& items, std::vector<int>* order, int begin, int end,
               const Box& centroids, int bins, bool use_sah) {
  if (use_sah) {
    const Split split = FindSahSplit(items, *order, begin, end, centroids, bins);
    if (split.axis >= 0) {
      const double lo = centroids.min[split.axis];
      const double scale = bins / (centroids.max[split.axis] - lo);
      const auto middle = std::partition(order->begin() + begin, order->begin() + end, [&](int i) {
        return BinOf(items[static_cast<size_t>(i)].centroid[split.axis], lo, scale, bins) < split.bin;
      });
      const int m = static_cast<int>(middle - order->begin());
      if (m > begin && m < end) return m;
    }
  }
  const Eigen::Vector3d extent = centroids.max - centroids.min;
  int axis = 0;
  if (extent.y() > extent[axis]) axis = 1;
  if (extent.z() > extent[axis]) axis = 2;
  const int middle = begin + (end - begin) / 2;
  std::nth_element(order->begin() + begin, order->begin() + middle, order->begin() + end, [&](int i, int j) {
    const double ci = items[static_cast<size_t>(i)].centroid[axis];
    const double cj = items[static_cast<size_t>(j)].centroid[axis];
    return ci < cj || (ci == cj && i < j);
  });
  return middle;
}

}  // namespace

void TriangleBvh::Build(std::vector<int>* order, const std::vector<WorldTriangle>& input) {
  // Boxes and centroids, indexed by input triangle.
  std::vector<BuildItem> items(input.size());
  for (const int i : *order) {
    BuildItem& item = items[static_cast<size_t>(i)];
    item.box = BoxOf(input[static_cast<size_t>(i)]);
    item.centroid = (item.box.min + item.box.max) * 0.5;
  }
  struct Pending {
    int begin, end, depth, parent;  // parent: the node whose second child this is, or -1
  };
  std::vector<Pending> pending = {{0, static_cast<int>(order->size()), 0, -1}};
  while (!pending.empty()) {
    const Pending task = pending.back();
    pending.pop_back();
    const int index = static_cast<int>(nodes_.size());
    if (task.parent >= 0) nodes_[static_cast<size_t>(task.parent)].first_or_second_child = index;
    Box box, centroids;
    for (int k = task.begin; k < task.end; ++k) {
      const BuildItem& item = items[static_cast<size_t>((*order)[k])];
      box.Grow(item.box);
      centroids.Grow(item.centroid);
    }
    Node node;
    // Padded a little beyond the rounding of the ray/box and ray/triangle tests.
    const double pad =
        1e-7 * ((box.max - box.min).maxCoeff() + box.min.cwiseAbs().cwiseMax(box.max.cwiseAbs()).maxCoeff());
    for (int a = 0; a < 3; ++a) {
      node.box_min[a] = RoundDown(box.min[a] - pad);
      node.box_max[a] = RoundUp(box.max[a] + pad);
    }
    if (task.end - task.begin <= options_.max_leaf_triangles) {
      node.first_or_second_child = task.begin;
      node.count = task.end - task.begin;
      nodes_.push_back(node);
      continue;
    }
    const int middle = SplitRange(items, order, task.begin, task.end, centroids, options_.sah_bins,
                                  task.depth < kMaxSahDepth);
    nodes_.push_back(node);  // inner: count 0, second child set when it is built
    // Depth first: the first child is built next (right after this node).
    pending.push_back({middle, task.end, task.depth + 1, index});
    pending.push_back({task.begin, middle, task.depth + 1, -1});
  }
}

template <bool kAnyHit>
std::optional<TriangleHit> TriangleBvh::Traverse(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                                                 double max_distance) const {
  if (nodes_.empty() || !(max_distance > options_.min_distance_m)) return std::nullopt;
  Eigen::Vector3d inv;
  for (int a = 0; a < 3; ++a) {
    // A zero component would give 0 * inf = NaN at a slab through the origin.
    const double d = direction[a] == 0.0 ? 1e-300 : direction[a];
    inv[a] = 1.0 / d;
  }
  const double min_distance = options_.min_distance_m;
  auto box_entry = [&](const Node& n, double t_max) {
    double t_near = min_distance, t_far = t_max;
    for (int a = 0; a < 3; ++a) {
      const double t0 = (n.box_min[a] - origin[a]) * inv[a];
      const double t1 = (n.box_max[a] - origin[a]) * inv[a];
      t_near = std::max(t_near, std::min(t0, t1));
      t_far = std::min(t_far, std::max(t0, t1));
    }
    return t_near <= t_far ? t_near : kInfinity;
  };
  std::optional<TriangleHit> best;
  double best_distance = max_distance;
  // Nodes still to visit, with the distance at which the ray enters them.
  struct Pending {
    int node;
    double entry;
  };
  Pending stack[kStackSize];
  int top = 0;
  int node_index = 0;
  if (box_entry(nodes_[0], best_distance) == kInfinity) return std::nullopt;
  while (true) {
    const Node& node = nodes_[static_cast<size_t>(node_index)];
    if (node.count > 0) {
      for (int k = node.first_or_second_child; k < node.first_or_second_child + node.count; ++k) {
        // Up to and including the best distance: ties go to the lower index.
        const double limit = best ? std::nextafter(best_distance, kInfinity) : best_distance;
        std::optional<TriangleHit> hit =
            IntersectTriangle(triangles_[static_cast<size_t>(k)], origin, direction, min_distance, limit);
        if (!hit) continue;
        hit->triangle = ids_[static_cast<size_t>(k)];
        if (kAnyHit) return hit;
        if (!best || hit->distance_m < best_distance || hit->triangle < best->triangle) {
          best = hit;
          best_distance = hit->distance_m;
        }
      }
    } else {
      const int first = node_index + 1, second = node.first_or_second_child;
      const double t_first = box_entry(nodes_[static_cast<size_t>(first)], best_distance);
      const double t_second = box_entry(nodes_[static_cast<size_t>(second)], best_distance);
      if (t_first != kInfinity || t_second != kInfinity) {
        const bool first_nearer = t_first <= t_second;
        const double t_farther = first_nearer ? t_second : t_first;
        if (t_farther != kInfinity) {
          SLAM_CHECK(top < kStackSize);
          stack[top++] = {first_nearer ? second : first, t_farther};
        }
        node_index = first_nearer ? first : second;
        continue;
      }
    }
    // The next node the ray enters before the best hit so far.
    while (top > 0 && stack[top - 1].entry > best_distance) --top;
    if (top == 0) break;
    node_index = stack[--top].node;
  }
  return best;
}

std::optional<TriangleHit> TriangleBvh::Intersect(const Eigen::Vector3d& origin,
                                                  const Eigen::Vector3d& unit_direction,
                                                  double max_distance) const {
  return Traverse<false>(origin, unit_direction, max_distance);
}

bool TriangleBvh::Occluded(const Eigen::Vector3d& origin, const Eigen::Vector3d& unit_direction,
                           double max_distance) const {
  return Traverse<true>(origin, unit_direction, max_distance).has_value();
}

}  // namespace duskmap
