#include "slam/synthetic/light/mesh_sun.h"

#include <algorithm>
#include <cmath>

#include "slam/core/check.h"

namespace duskmap {
namespace {

// Index of grid point (i, j): rows j = 0..n hold n + 1 - j points each.
int GridIndex(int n, int i, int j) { return j * (n + 1) - j * (j - 1) / 2 + i; }

}  // namespace

float TriangleSunSamples::At(float b1, float b2) const {
  SLAM_CHECK(intervals > 0);
  const int n = intervals;
  const float u = std::clamp(b1, 0.0f, 1.0f) * n;
  const float v = std::clamp(b2, 0.0f, 1.0f) * n;
  int i = std::min(static_cast<int>(u), n - 1);
  int j = std::min(static_cast<int>(v), n - 1);
  if (i + j > n - 1) {  // past the last cell of its row (rounding at the far edge)
    if (i > j) {
      i = n - 1 - j;
    } else {
      j = n - 1 - i;
    }
  }
  const float fu = std::clamp(u - i, 0.0f, 1.0f);
  const float fv = std::clamp(v - j, 0.0f, 1.0f);
  const float v00 = visible[static_cast<size_t>(GridIndex(n, i, j))];
  const float v10 = visible[static_cast<size_t>(GridIndex(n, i + 1, j))];
  const float v01 = visible[static_cast<size_t>(GridIndex(n, i, j + 1))];
  if (fu + fv <= 1.0f || i + j + 2 > n) {  // the cell's lower triangle (the only one on the diagonal)
    return v00 * (1.0f - fu - fv) + v10 * fu + v01 * fv;
  }
  const float v11 = visible[static_cast<size_t>(GridIndex(n, i + 1, j + 1))];
  return v11 * (fu + fv - 1.0f) + v10 * (1.0f - fv) + v01 * (1.0f - fu);
}

TriangleSunSamples SampleTriangleSun(const std::array<Eigen::Vector3d, 3>& corners_in_world,
                                     const Eigen::Vector3d& offset_in_world,
                                     const Eigen::Vector3d& to_sun_in_world, double spacing_m,
                                     int max_intervals, const SunRayTest& reaches) {
  SLAM_CHECK(spacing_m > 0.0 && max_intervals >= 1);
  const Eigen::Vector3d& c0 = corners_in_world[0];
  const Eigen::Vector3d e1 = corners_in_world[1] - c0;
  const Eigen::Vector3d e2 = corners_in_world[2] - c0;
  const double longest = std::max({e1.norm(), e2.norm(), (e2 - e1).norm()});
  TriangleSunSamples samples;
  samples.intervals = std::clamp(static_cast<int>(std::ceil(longest / spacing_m)), 1, max_intervals);
  const int n = samples.intervals;
  samples.visible.reserve(static_cast<size_t>((n + 1) * (n + 2) / 2));
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i + j <= n; ++i) {
      const Eigen::Vector3d p = c0 + (static_cast<double>(i) / n) * e1 +
                                (static_cast<double>(j) / n) * e2 + offset_in_world;
      samples.visible.push_back(reaches(p, to_sun_in_world) ? 1.0f : 0.0f);
    }
  }
  return samples;
}

}  // namespace duskmap
