#include "slam/registration/guided_matching.h"

#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_map>

#include "slam/core/check.h"
#include "slam/registration/nndr_matcher.h"

namespace duskmap {
namespace {

// Uniform grid over the query keypoints with cells of the window size, so a
// radius search visits at most 3x3 cells.
class KeypointGrid {
 public:
  KeypointGrid(const std::vector<cv::KeyPoint>& keypoints, double cell_px)
      : keypoints_(keypoints), cell_px_(cell_px) {
    for (int i = 0; i < static_cast<int>(keypoints.size()); ++i) {
      const cv::Point2f& p = keypoints[i].pt;
      if (!std::isfinite(p.x) || !std::isfinite(p.y)) continue;
      cells_[Key(Cell(p.x), Cell(p.y))].push_back(i);
    }
  }

  void Radius(double u, double v, double radius_px, std::vector<int>* found) const {
    found->clear();
    const long cu = Cell(u), cv = Cell(v);
    const double radius_sq = radius_px * radius_px;
    for (long du = -1; du <= 1; ++du) {
      for (long dv = -1; dv <= 1; ++dv) {
        const auto it = cells_.find(Key(cu + du, cv + dv));
        if (it == cells_.end()) continue;
        for (int i : it->second) {
          const double ex = keypoints_[i].pt.x - u, ey = keypoints_[i].pt.y - v;
          if (ex * ex + ey * ey <= radius_sq) found->push_back(i);
        }
      }
    }
  }

 private:
  long Cell(double x) const { return static_cast<long>(std::floor(x / cell_px_)); }
  // The two cell indices in one 64-bit key (shifted as unsigned: a negative
  // cu shifted as signed is undefined behaviour).
  static uint64_t Key(long cu, long cv) {
    return (static_cast<uint64_t>(cu) << 32) ^ static_cast<uint32_t>(cv);
  }

  const std::vector<cv::KeyPoint>& keypoints_;
  double cell_px_;
  std::unordered_map<uint64_t, std::vector<int>> cells_;
};

}  // namespace

void GuidedMatchingOptions::Check() const {
  SLAM_THROW_IF_NOT(ConfigError, window_px > 0.0 && std::isfinite(window_px))
      << "GuidedMatchingOptions.window_px: must be finite and > 0, got " << window_px;
  SLAM_THROW_IF_NOT(ConfigError, float_ratio > 0.0 && float_ratio <= 1.0)
      << "GuidedMatchingOptions.float_ratio: must be in (0, 1], got " << float_ratio;
  SLAM_THROW_IF_NOT(ConfigError, binary_ratio > 0.0 && binary_ratio <= 1.0)
      << "GuidedMatchingOptions.binary_ratio: must be in (0, 1], got " << binary_ratio;
}

std::vector<cv::DMatch> MatchInProjectionWindow(const GuidedMatchingOptions& options,
                                                const FrameFeatures& map_node,
                                                const FrameFeatures& query,
                                                const PinholeCamera& query_camera,
                                                const Rigid3d& query_from_node) {
  options.Check();
  CheckFeatures(map_node, "map node features");
  CheckFeatures(query, "query features");
  std::vector<cv::DMatch> matches;
  if (map_node.empty() || query.empty() || map_node.points_in_camera.empty()) return matches;
  CheckComparable(map_node, query);
  SLAM_CHECK(query_from_node.IsFinite());

  const double ratio =
      map_node.kind == DescriptorKind::kFloat ? options.float_ratio : options.binary_ratio;
  const KeypointGrid grid(query.keypoints, options.window_px);
  std::vector<char> used(query.size(), 0);
  std::vector<int> candidates;
  for (int j = 0; j < static_cast<int>(map_node.size()); ++j) {
    if (!map_node.HasPoint(j)) continue;
    Eigen::Vector2d pixel;
    const Eigen::Vector3d point = map_node.points_in_camera[j].cast<double>();
    if (!query_camera.Project(query_from_node * point, &pixel)) continue;
    if (!query_camera.InImage(pixel.x(), pixel.y())) continue;
    grid.Radius(pixel.x(), pixel.y(), options.window_px, &candidates);
    if (candidates.empty()) continue;
    int best = candidates[0];
    double best_distance = 0.0;
    if (candidates.size() >= 2) {
      double second_distance = std::numeric_limits<double>::infinity();
      best_distance = std::numeric_limits<double>::infinity();
      for (int i : candidates) {
        const double d =
            DescriptorDistance(query.descriptors, i, map_node.descriptors, j, map_node.kind);
        if (d < best_distance) {
          second_distance = best_distance;
          best_distance = d;
          best = i;
        } else if (d < second_distance) {
          second_distance = d;
        }
      }
      if (!(best_distance < ratio * second_distance)) continue;
    } else {
      best_distance =
          DescriptorDistance(query.descriptors, best, map_node.descriptors, j, map_node.kind);
    }
    if (used[best]) continue;
    used[best] = 1;
    matches.emplace_back(best, j, static_cast<float>(best_distance));
  }
  return matches;
}

}  // namespace duskmap
