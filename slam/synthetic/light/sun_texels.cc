#include "slam/synthetic/light/sun_texels.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

#include <Eigen/Geometry>
#include <opencv2/imgproc.hpp>

#include "slam/core/check.h"

namespace duskmap {
namespace {

// Directions spread evenly over the sun's disc (Vogel's spiral: radius
// sqrt((k + 0.5) / n), golden-angle steps), as offsets in the plane
// orthogonal to the sun's direction, in radians.
std::vector<Eigen::Vector2d> DiscOffsets(int n, double radius_rad) {
  constexpr double kGoldenAngle = 2.39996322972865332;
  std::vector<Eigen::Vector2d> offsets(static_cast<size_t>(n));
  for (int k = 0; k < n; ++k) {
    const double r = radius_rad * std::sqrt((k + 0.5) / n);
    offsets[static_cast<size_t>(k)] = r * Eigen::Vector2d(std::cos(k * kGoldenAngle), std::sin(k * kGoldenAngle));
  }
  return offsets;
}

}  // namespace

void SunTexelOptions::Check() const {
  SLAM_THROW_IF_NOT(ConfigError, sun_angular_radius_rad >= 0.0 && sun_angular_radius_rad < 0.1)
      << "sun texels: the sun's angular radius must be in [0, 0.1) rad, got " << sun_angular_radius_rad;
  SLAM_THROW_IF_NOT(ConfigError, max_penumbra_m >= 0.0 && max_penumbra_m <= 1.0)
      << "sun texels: max_penumbra_m must be in [0, 1], got " << max_penumbra_m;
  SLAM_THROW_IF_NOT(ConfigError, samples_per_texel >= 1 && samples_per_texel <= 256)
      << "sun texels: samples_per_texel must be in [1, 256], got " << samples_per_texel;
}

cv::Mat SunVisibility(const Quad& quad, cv::Size texels, const Eigen::Vector3d& to_sun_in_world,
                      const SunRayTest& reaches, const SunTexelOptions& options) {
  options.Check();
  SLAM_CHECK(texels.width >= 1 && texels.height >= 1);
  const double du = quad.size_u_m / texels.width, dv = quad.size_v_m / texels.height;
  const auto point_at = [&](double col, double row) { return quad.PointAt(col * du, row * dv); };

  // The centre test everywhere.
  cv::Mat centre(texels, CV_8U);
  for (int r = 0; r < texels.height; ++r) {
    uint8_t* out = centre.ptr<uint8_t>(r);
    for (int c = 0; c < texels.width; ++c) out[c] = reaches(point_at(c + 0.5, r + 0.5), to_sun_in_world) ? 1 : 0;
  }
  cv::Mat visibility;
  centre.convertTo(visibility, CV_32F);

  // Where the penumbra may be: within max_penumbra_m of a change.
  const int reach_u = static_cast<int>(std::ceil(options.max_penumbra_m / du));
  const int reach_v = static_cast<int>(std::ceil(options.max_penumbra_m / dv));
  const cv::Mat kernel = cv::getStructuringElement(cv::MORPH_RECT, cv::Size(2 * reach_u + 1, 2 * reach_v + 1));
  cv::Mat grown, shrunk;
  cv::dilate(centre, grown, kernel, cv::Point(-1, -1), 1, cv::BORDER_REPLICATE);
  cv::erode(centre, shrunk, kernel, cv::Point(-1, -1), 1, cv::BORDER_REPLICATE);

  // The sample pattern: positions on a grid over the texel, directions on
  // the disc, paired by a stride coprime to the count (so that neither
  // follows the other's order).
  const int n = options.samples_per_texel;
  const int grid = std::max(1, static_cast<int>(std::lround(std::sqrt(static_cast<double>(n)))));
  const std::vector<Eigen::Vector2d> disc = DiscOffsets(n, options.sun_angular_radius_rad);
  const Eigen::Vector3d axis = to_sun_in_world.normalized();
  const Eigen::Vector3d e1 = axis.unitOrthogonal(), e2 = axis.cross(e1);
  std::vector<Eigen::Vector3d> directions(static_cast<size_t>(n));
  std::vector<Eigen::Vector2d> positions(static_cast<size_t>(n));
  int stride = 7;
  while (std::gcd(stride, n) != 1) ++stride;
  for (int k = 0; k < n; ++k) {
    const Eigen::Vector2d& o = disc[static_cast<size_t>((k * stride) % n)];
    directions[static_cast<size_t>(k)] = (axis + std::tan(o.x()) * e1 + std::tan(o.y()) * e2).normalized();
    positions[static_cast<size_t>(k)] = Eigen::Vector2d(((k % grid) + 0.5) / grid, (((k / grid) % grid) + 0.5) / grid);
  }
  for (int r = 0; r < texels.height; ++r) {
    const uint8_t* g = grown.ptr<uint8_t>(r);
    const uint8_t* s = shrunk.ptr<uint8_t>(r);
    float* out = visibility.ptr<float>(r);
    for (int c = 0; c < texels.width; ++c) {
      if (g[c] == s[c]) continue;  // no change nearby: the centre test stands
      int lit = 0;
      for (int k = 0; k < n; ++k) {
        const Eigen::Vector2d& p = positions[static_cast<size_t>(k)];
        lit += reaches(point_at(c + p.x(), r + p.y()), directions[static_cast<size_t>(k)]) ? 1 : 0;
      }
      out[c] = static_cast<float>(lit) / static_cast<float>(n);
    }
  }
  return visibility;
}

}  // namespace duskmap
