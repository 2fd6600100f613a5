// The sun per pixel over mesh triangles whose vertices disagree about it
// (mesh_sun.h): the barycentric grid's interpolation, its sampling, and a
// sun patch's edge across a furniture mesh drawn straight.
#include "slam/synthetic/light/mesh_sun.h"

#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "one_window_scene.h"
#include "slam/core/check.h"
#include "slam/synthetic/light/lighting.h"
#include "slam/synthetic/render/renderer.h"
#include "slam/synthetic/scene/scene_mesh.h"
#include "small_camera.h"

namespace duskmap {
namespace {

TEST(TriangleSunSamples, InterpolationIsExactForALinearField) {
  // Samples of f = 0.2 + 0.5 b1 - 0.3 b2 on an n = 5 grid: At is linear in
  // each cell, so it reproduces f everywhere, corners and edges included.
  TriangleSunSamples samples;
  samples.intervals = 5;
  for (int j = 0; j <= 5; ++j) {
    for (int i = 0; i + j <= 5; ++i) samples.visible.push_back(0.2f + 0.5f * i / 5 - 0.3f * j / 5);
  }
  ASSERT_EQ(samples.visible.size(), 21u);
  for (int a = 0; a <= 40; ++a) {
    for (int b = 0; a + b <= 40; ++b) {
      const float b1 = a / 40.0f, b2 = b / 40.0f;
      EXPECT_NEAR(samples.At(b1, b2), 0.2f + 0.5f * b1 - 0.3f * b2, 1e-5f) << b1 << " " << b2;
    }
  }
  EXPECT_FLOAT_EQ(samples.At(0, 0), 0.2f);
  EXPECT_FLOAT_EQ(samples.At(1, 0), 0.7f);
  EXPECT_FLOAT_EQ(samples.At(0, 1), -0.1f);
}

TEST(SampleTriangleSun, SamplesTheGridOfTheSpacingAndCapsIt) {
  // A right triangle with 0.1 m legs in z = 0; the sun reaches x < 0.04.
  const std::array<Eigen::Vector3d, 3> corners = {
      Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0.1, 0, 0), Eigen::Vector3d(0, 0.1, 0)};
  int calls = 0;
  const SunRayTest reaches = [&](const Eigen::Vector3d& p, const Eigen::Vector3d& to_sun) {
    ++calls;
    EXPECT_DOUBLE_EQ(p.z(), 0.001);  // moved off the surface
    EXPECT_EQ(to_sun, Eigen::Vector3d::UnitZ());
    return p.x() < 0.04;
  };
  const TriangleSunSamples s =
      SampleTriangleSun(corners, Eigen::Vector3d(0, 0, 0.001), Eigen::Vector3d::UnitZ(), 0.005, 100, reaches);
  EXPECT_EQ(s.intervals, 29);  // the hypotenuse, 0.1414 m, over 5 mm
  EXPECT_EQ(calls, 30 * 31 / 2);
  EXPECT_FLOAT_EQ(s.At(0.0f, 0.5f), 1.0f);   // x = 0
  EXPECT_FLOAT_EQ(s.At(0.6f, 0.2f), 0.0f);   // x = 0.06
  EXPECT_FLOAT_EQ(s.At(0.3f, 0.1f), 1.0f);   // x = 0.03, between two lit samples
  EXPECT_GT(s.At(0.38f, 0.1f), 0.9f);         // x = 0.038: 0.2 mm before the last lit sample
  EXPECT_EQ(SampleTriangleSun(corners, {0, 0, 0.001}, Eigen::Vector3d::UnitZ(), 0.005, 8, reaches).intervals, 8);
}

// OneWindowScene's window, and a 1 m square of furniture 0.5 m above the
// floor, facing up, where the sun patch's side edge (from the window's edge
// at y = 1) crosses it on a slant to the mesh's 12 cm edge splits.
Scene WindowAndTable() {
  Scene scene = OneWindowScene();
  TriangleMesh top;
  top.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  top.normals = {{0, 0, 1}};
  Material white;
  white.diffuse_bgr = cv::Vec3f(1, 1, 1);
  top.materials = {white};
  MeshTriangle a, b;
  a.position = {0, 1, 2};  // counter-clockwise seen from above
  b.position = {0, 2, 3};
  a.normal = b.normal = {0, 0, 0};
  top.triangles = {a, b};
  scene.SetMeshes({MakeSceneMesh(
      top, Rigid3d(Eigen::Quaterniond::Identity(), Eigen::Vector3d(0.4, 0.4, 0.5)), 0, "table")});
  return scene;
}

TEST(PrepareSessionRadiance, TheSunPerSampleDrawsAPatchEdgeStraightAcrossAMesh) {
  const Scene scene = WindowAndTable();
  LightingOptions options;
  const SessionLighting l = LowSunAlone(scene, &options);
  const Eigen::Vector3d& to_sun = l.sun_direction_in_world;
  const double full = 1000.0 * to_sun.z() / M_PI;  // a sunlit white pixel, nits

  // Looking straight down at the square from 1.5 m above it.
  const Renderer renderer(scene, SmallCamera());
  Eigen::Matrix3d down;
  down << 1, 0, 0, 0, -1, 0, 0, 0, -1;
  const Rigid3d world_from_camera(Eigen::Quaterniond(down), Eigen::Vector3d(0.9, 0.9, 2.0));
  options.mesh_sun_per_sample = true;
  const SessionRadiance per_sample = PrepareSessionRadiance(scene, l, options);
  options.mesh_sun_per_sample = false;
  const SessionRadiance per_vertex = PrepareSessionRadiance(scene, l, options);
  ASSERT_EQ(per_sample.mesh_sun.size(), 1u);
  EXPECT_TRUE(per_vertex.mesh_sun.empty());
  EXPECT_EQ(per_sample.mesh_vertex_light, per_vertex.mesh_vertex_light);  // the vertices' light is the same
  const size_t sampled = per_sample.mesh_sun[0].samples.size();
  EXPECT_GT(sampled, 10u);  // the triangles the edge crosses
  EXPECT_LT(sampled, per_sample.mesh_sun[0].triangle_samples.size() / 4);
  RenderedView sample_view, vertex_view;
  renderer.Render(per_sample, world_from_camera, &sample_view);
  renderer.Render(per_vertex, world_from_camera, &vertex_view);

  const PinholeCamera camera = SmallCamera();
  const int mesh_id = static_cast<int>(scene.quads.size());
  double sample_error = 0.0, vertex_error = 0.0;
  int pixels = 0, edge_pixels = 0;
  for (int row = 0; row < camera.height; ++row) {
    for (int col = 0; col < camera.width; ++col) {
      if (sample_view.surface_id.at<int>(row, col) != mesh_id) continue;
      ++pixels;
      // The pixel's point on the square (z = 0.5), and how far inside the
      // window (metres on the window) its ray towards the sun passes.
      const double x = 0.9 + (col - camera.cx) / camera.fx * 1.5;
      const double y = 0.9 - (row - camera.cy) / camera.fy * 1.5;
      const double t = -x / to_sun.x();
      const double wy = y + t * to_sun.y(), wz = 0.5 + t * to_sun.z();
      const double inside_m = std::min({wy + 1.0, 1.0 - wy, wz - 0.9, 2.1 - wz});
      const double expected = inside_m >= 0.0 ? 1.0 : 0.0;
      const double with_samples = sample_view.radiance.at<cv::Vec3f>(row, col)[1] / full;
      const double with_vertices = vertex_view.radiance.at<cv::Vec3f>(row, col)[1] / full;
      // A pixel is 11 mm here and the grid 5 mm: beyond 2 cm both are exact
      // (the vertices' too, 12 cm from the edge).
      if (std::abs(inside_m) > 0.02) {
        EXPECT_NEAR(with_samples, expected, 1e-3) << row << " " << col;
        if (std::abs(inside_m) > 0.15) EXPECT_NEAR(with_vertices, expected, 1e-3) << row << " " << col;
      } else {
        ++edge_pixels;
      }
      sample_error += std::abs(with_samples - expected);
      vertex_error += std::abs(with_vertices - expected);
    }
  }
  ASSERT_GT(pixels, 5000);
  ASSERT_GT(edge_pixels, 50);
  // Over the square: the samples are off by about the half-pixel band along
  // the edge, the vertices by the gradient between them.
  EXPECT_LT(sample_error, 0.25 * vertex_error) << sample_error / pixels << " against " << vertex_error / pixels;
}

TEST(LightingOptions, TheMeshSunSpacingIsChecked) {
  LightingOptions options;
  options.mesh_sun_sample_m = 0.0;
  EXPECT_THROW(options.Check(), ConfigError);
  options.mesh_sun_sample_m = 0.2;
  EXPECT_THROW(options.Check(), ConfigError);
  options.mesh_sun_sample_m = 0.005;
  EXPECT_NO_THROW(options.Check());
}

}  // namespace
}  // namespace duskmap
