// The sun's visibility over a quad's texture, texel by texel: what the sun
// patch through a window looks like at the texture's own resolution, with
// the edges antialiased and the penumbra of the sun's disc, instead of the
// light map's nodes every lighting.light_texel_m (whose bilinear
// interpolation of a hard yes/no draws a patch's slanted edges as stairs of
// that spacing).
#pragma once

#include <functional>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "slam/synthetic/scene/scene.h"

namespace duskmap {

struct SunTexelOptions {
  // The sun's angular radius (0.2666 degrees, mean).
  double sun_angular_radius_rad = 0.004653;
  // The widest penumbra to resolve, metres: the disc's angular diameter
  // times the farthest occluder (a window frame 6 m away: 5.6 cm). Texels
  // farther than this from where the centre test changes take the centre
  // test's value.
  double max_penumbra_m = 0.056;
  // Samples per texel where the penumbra may be: positions on a 4 x 4 grid
  // over the texel, each with its own direction on the sun's disc.
  int samples_per_texel = 16;

  void Check() const;
};

// Whether the sun's light reaches `point_in_world` along the unit
// `to_sun_in_world` (through a window, past every occluder).
using SunRayTest = std::function<bool(const Eigen::Vector3d& point_in_world, const Eigen::Vector3d& to_sun_in_world)>;

// The fraction of the sun's disc visible from each texel of `quad`'s
// `texels`-sized texture (CV_32F, rows along v): 0 or 1 away from a patch's
// edges (one test at the texel's centre towards the sun's centre), the mean
// of `samples_per_texel` tests over the texel's area and the disc within
// max_penumbra_m of a change. Deterministic: the sample pattern is fixed.
cv::Mat SunVisibility(const Quad& quad, cv::Size texels, const Eigen::Vector3d& to_sun_in_world,
                      const SunRayTest& reaches, const SunTexelOptions& options = SunTexelOptions());

}  // namespace duskmap
