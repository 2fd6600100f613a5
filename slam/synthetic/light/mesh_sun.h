// The sun over a furniture mesh's triangles where their vertices disagree
// about it. The meshes are lit per vertex (edges split at 12 cm), so a sun
// patch's edge across a triangle became a gradient between a lit and an
// unlit vertex: a blotchy patch on the sofa of every day session's docking
// view. For such a triangle the sun's visibility is sampled on a
// barycentric grid of about mesh_sun_sample_m, and the renderer adds the sun
// per pixel from it (linear within the grid's cells).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "slam/synthetic/light/sun_texels.h"

namespace duskmap {

// The sun's visibility on a triangle, sampled at the barycentric points
// (i/n, j/n) for i, j >= 0, i + j <= n: weight i/n on corner 1, j/n on
// corner 2.
struct TriangleSunSamples {
  int intervals = 0;            // n
  std::vector<float> visible;   // (n + 1)(n + 2) / 2 samples, 0 or 1, row j after row j - 1

  // The visibility at barycentric weights (b1, b2) of corners 1 and 2,
  // linear within the grid's triangular cells (exact for a linear field).
  float At(float b1, float b2) const;
};

// Samples `reaches` (towards the sun's centre) at the grid's points of the
// triangle `corners_in_world`, each point moved by `offset_in_world` off the
// surface. The grid has ceil(longest edge / spacing_m) intervals, at least 1
// and at most max_intervals.
TriangleSunSamples SampleTriangleSun(const std::array<Eigen::Vector3d, 3>& corners_in_world,
                                     const Eigen::Vector3d& offset_in_world,
                                     const Eigen::Vector3d& to_sun_in_world, double spacing_m,
                                     int max_intervals, const SunRayTest& reaches);

// The sun's part in a mesh's light (SessionRadiance::mesh_sun).
struct MeshSun {
  std::vector<cv::Vec3f> vertex_sun;        // per vertex: the unshadowed sun term / pi (nits per unit albedo)
  std::vector<uint8_t> vertex_sun_visible;  // per vertex: whether its light (mesh_vertex_light) includes it
  std::vector<int> triangle_samples;        // per triangle: index into `samples`, -1 when its vertices agree
  std::vector<TriangleSunSamples> samples;
};

}  // namespace duskmap
