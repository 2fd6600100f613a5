// Furniture meshes in the scene: edge splitting without cracks, rendering
// beside quads, texture lookups at ground-truth poses, cast shadows.
#include <map>
#include <utility>

#include <gtest/gtest.h>

#include "small_camera.h"

#include "slam/core/check.h"
#include "slam/synthetic/light/lighting.h"
#include "slam/synthetic/render/renderer.h"
#include "slam/synthetic/scene/scene_mesh.h"

namespace duskmap {
namespace {

// A square of `size_m` in the furniture frame's x-z plane (y = 0), facing
// -y, as two triangles, textured with `texture` (may be empty).
TriangleMesh Square(double size_m, const cv::Mat& texture) {
  TriangleMesh mesh;
  const float s = static_cast<float>(size_m);
  mesh.positions = {{0, 0, 0}, {s, 0, 0}, {s, 0, s}, {0, 0, s}};
  mesh.texcoords = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  Material material;
  material.diffuse_bgr = cv::Vec3f(1, 1, 1);
  material.diffuse_texture = texture;
  mesh.materials = {material};
  MeshTriangle a, b;
  // Counter-clockwise seen from -y: (0,0,0) -> (s,0,0) -> (s,0,s).
  a.position = {0, 1, 2};
  a.texcoord = {0, 1, 2};
  b.position = {0, 2, 3};
  b.texcoord = {0, 2, 3};
  mesh.triangles = {a, b};
  return mesh;
}

// A closed box [0, s]^3 with outward faces, no texture.
TriangleMesh Box(float s) {
  TriangleMesh mesh;
  for (int i = 0; i < 8; ++i) mesh.positions.push_back({(i & 1) * s, ((i >> 1) & 1) * s, ((i >> 2) & 1) * s});
  mesh.materials = {Material()};
  const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& f : faces) {
    MeshTriangle a, b;
    a.position = {f[0], f[1], f[2]};
    b.position = {f[0], f[2], f[3]};
    mesh.triangles.push_back(a);
    mesh.triangles.push_back(b);
  }
  return mesh;
}

Quad FloorQuad(double size_m) {
  Quad q;
  q.origin_in_world = Eigen::Vector3d(-size_m / 2, -size_m / 2, 0);
  q.u_axis = Eigen::Vector3d::UnitX();
  q.v_axis = Eigen::Vector3d::UnitY();
  q.size_u_m = q.size_v_m = size_m;
  q.albedo = cv::Mat(32, 32, CV_32FC3, cv::Scalar(0.5, 0.5, 0.5));
  return q;
}

TEST(MakeSceneMesh, SplitsLongEdgesWithoutCracks) {
  const SceneMesh mesh = MakeSceneMesh(Square(1.0, cv::Mat()), Rigid3d(), 0, "square", {0.12, 100000});
  double area = 0.0;
  // Undirected edges by their end points' exact coordinates -> uses: the
  // triangles on either side may hold different vertices (normals, texture
  // coordinates) at bitwise-equal positions, which is what a crack-free
  // raster needs.
  using Point = std::array<float, 3>;
  std::map<std::pair<Point, Point>, int> edges;
  const auto point = [&](int i) {
    const Eigen::Vector3f& p = mesh.positions_in_world[i];
    return Point{p.x(), p.y(), p.z()};
  };
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3f a = mesh.positions_in_world[t[0]], b = mesh.positions_in_world[t[1]],
                          c = mesh.positions_in_world[t[2]];
    area += 0.5 * (b - a).cross(c - a).norm();
    // Orientation kept: the square faces -y.
    EXPECT_LT((b - a).cross(c - a).y(), 0.0f);
    for (int e = 0; e < 3; ++e) {
      const int p = t[e], q = t[(e + 1) % 3];
      EXPECT_LE((mesh.positions_in_world[p] - mesh.positions_in_world[q]).norm(), 0.12f + 1e-6f);
      ++edges[std::minmax(point(p), point(q))];
    }
  }
  EXPECT_NEAR(area, 1.0, 1e-5);
  // Every edge is used twice (inside) or once (on the square's border); a
  // T-junction would leave an inner edge used once.
  double border_m = 0.0;
  for (const auto& [edge, uses] : edges) {
    ASSERT_LE(uses, 2);
    if (uses == 1) {
      border_m += (Eigen::Vector3f(edge.first.data()) - Eigen::Vector3f(edge.second.data())).norm();
    }
  }
  EXPECT_NEAR(border_m, 4.0, 1e-4);
  EXPECT_GT(mesh.triangles.size(), 100u);
  // Normals: the face's, unit, for corners without one.
  for (const Eigen::Vector3f& n : mesh.normals_in_world) EXPECT_NEAR(n.y(), -1.0f, 1e-5f);
}

TEST(MakeSceneMesh, TooManyTrianglesNamesThePiece) {
  try {
    MakeSceneMesh(Square(2.0, cv::Mat()), Rigid3d(), 0, "Big table", {0.01, 1000});
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("Big table: more than 1000 triangles"), std::string::npos) << e.what();
  }
}

// A textured square 2 m in front of two cameras: each pixel's 3D point
// (from depth) seen by the other camera shows the same texture colour.
TEST(RenderMeshes, ATexturedMeshLandsOnTheSameSurfacePointFromTwoPoses) {
  // A smooth texture (a colour ramp in both directions), so that a sub-pixel
  // difference in where a point lands changes its colour little.
  cv::Mat texture(64, 64, CV_32FC3);
  for (int r = 0; r < 64; ++r) {
    for (int c = 0; c < 64; ++c) texture.at<cv::Vec3f>(r, c) = cv::Vec3f(c / 63.0f, r / 63.0f, 0.5f);
  }
  Scene scene;
  scene.room_names = {"room"};
  // The square at y = 2 (world), x and z in [-1, 1], facing -y (the cameras).
  const Rigid3d world_from_furniture(Eigen::Quaterniond::Identity(), Eigen::Vector3d(-1, 2, -1));
  scene.SetMeshes({MakeSceneMesh(Square(2.0, texture), world_from_furniture, 0, "square")});
  SessionRadiance radiance;
  radiance.mesh_vertex_light = {std::vector<cv::Vec3f>(scene.meshes[0].positions_in_world.size(), cv::Vec3f(1, 1, 1))};
  const PinholeCamera camera = SmallCamera();
  const Renderer renderer(scene, camera);
  const Eigen::Matrix3d looking_north = CameraRotationFromYawPitchRoll(M_PI / 2, 0, 0);
  const Rigid3d world_from_a(Eigen::Quaterniond(looking_north), Eigen::Vector3d(0, 0, 0));
  const Rigid3d world_from_b(Eigen::Quaterniond(CameraRotationFromYawPitchRoll(M_PI / 2 + 0.2, 0.1, 0.05)),
                             Eigen::Vector3d(0.3, 0.4, -0.1));
  RenderedView a, b;
  renderer.Render(radiance, world_from_a, &a);
  renderer.Render(radiance, world_from_b, &b);
  int checked = 0;
  for (int v = 5; v < camera.height; v += 7) {
    for (int u = 5; u < camera.width; u += 7) {
      if (a.surface_id.at<int>(v, u) != 0) continue;  // quads: none; the mesh is 0 + 0
      const double z = a.depth_m.at<float>(v, u);
      const Eigen::Vector3d in_a((u - camera.cx) / camera.fx * z, (v - camera.cy) / camera.fy * z, z);
      const Eigen::Vector3d world = world_from_a * in_a;
      EXPECT_NEAR(world.y(), 2.0, 1e-4);  // on the square's plane
      Eigen::Vector2d pixel;
      ASSERT_TRUE(camera.Project(world_from_b.Inverse() * world, &pixel));
      const int ub = static_cast<int>(std::lround(pixel.x())), vb = static_cast<int>(std::lround(pixel.y()));
      if (ub < 1 || vb < 1 || ub >= camera.width - 1 || vb >= camera.height - 1) continue;
      if (b.surface_id.at<int>(vb, ub) != 0) continue;
      ++checked;
      // The texture changes by 1/63 per texel over 2 m / 64 texels: within
      // half a pixel of a 2 m distant point the colour differs by < 0.01.
      const cv::Vec3f ca = a.radiance.at<cv::Vec3f>(v, u), cb = b.radiance.at<cv::Vec3f>(vb, ub);
      EXPECT_NEAR(ca[0], cb[0], 0.012) << u << "," << v;
      EXPECT_NEAR(ca[1], cb[1], 0.012) << u << "," << v;
    }
  }
  EXPECT_GT(checked, 100);
  // The colour is the texture's: at the image centre, the square's centre.
  const cv::Vec3f centre = a.radiance.at<cv::Vec3f>(60, 80);
  EXPECT_NEAR(centre[0], 0.5, 0.03);
  EXPECT_NEAR(centre[1], 0.5, 0.03);
  EXPECT_NEAR(a.depth_m.at<float>(60, 80), 2.0f, 1e-3f);
  EXPECT_NEAR(a.cos_incidence.at<float>(60, 80), 1.0f, 1e-3f);
}

TEST(RenderMeshes, AMeshInFrontOfAQuadHidesIt) {
  Scene scene;
  scene.room_names = {"room"};
  Quad wall = FloorQuad(4.0);  // turned into a wall 3 m ahead, facing the camera
  wall.origin_in_world = Eigen::Vector3d(-2, 3, -2);
  wall.u_axis = Eigen::Vector3d::UnitX();
  wall.v_axis = Eigen::Vector3d::UnitZ();
  scene.quads.push_back(wall);
  scene.SetMeshes({MakeSceneMesh(Square(1.0, cv::Mat()), Rigid3d(Eigen::Quaterniond::Identity(),
                                                                 Eigen::Vector3d(-0.5, 2, -0.5)),
                                 0, "square")});
  SessionRadiance radiance;
  radiance.quads = {cv::Mat(8, 8, CV_32FC3, cv::Scalar(0.2, 0.2, 0.2))};
  radiance.mesh_vertex_light = {std::vector<cv::Vec3f>(scene.meshes[0].positions_in_world.size(), cv::Vec3f(1, 1, 1))};
  const Renderer renderer(scene, SmallCamera());
  RenderedView view;
  renderer.Render(radiance, Rigid3d(Eigen::Quaterniond(CameraRotationFromYawPitchRoll(M_PI / 2, 0, 0)),
                                    Eigen::Vector3d::Zero()),
                  &view);
  EXPECT_EQ(view.surface_id.at<int>(60, 80), 1);  // quads.size() + mesh 0
  EXPECT_NEAR(view.depth_m.at<float>(60, 80), 2.0f, 1e-3f);
  EXPECT_NEAR(view.radiance.at<cv::Vec3f>(60, 80)[1], 1.0f, 1e-4f);  // Kd 1 x light 1
  EXPECT_EQ(view.surface_id.at<int>(5, 5), 0);  // the wall around it
  EXPECT_NEAR(view.depth_m.at<float>(5, 5), 3.0f, 1e-3f);
  // The quad-only entry point refuses a scene with meshes.
  EXPECT_DEATH(renderer.Render(radiance.quads, Rigid3d(), &view), "needs its SessionRadiance");
}

// A lamp 2 m above a floor and a 0.4 m box between: the floor under the box
// is in its shadow, the floor beside it lit; the box's top is lit, its
// bottom (facing the floor) only by the ambient term.
TEST(PrepareSessionRadiance, AMeshCastsAShadowAndIsLitPerVertex) {
  Scene scene;
  scene.room_names = {"room"};
  scene.quads.push_back(FloorQuad(4.0));
  Lamp lamp;
  lamp.name = "lamp";
  lamp.position_in_world = Eigen::Vector3d(0, 0, 2.0);
  lamp.intensity_cd = 100.0;
  scene.lamps.push_back(lamp);
  scene.SetMeshes({MakeSceneMesh(Box(0.4f), Rigid3d(Eigen::Quaterniond::Identity(), Eigen::Vector3d(-0.2, -0.2, 0.5)),
                                 0, "box")});
  LightingOptions options;
  options.ambient_fraction = 0.0;
  options.ambient_leak = 0.0;
  const SessionLighting lighting = ComputeSessionLighting(options, scene, 22.0);  // night: the lamp alone
  const SessionRadiance radiance = PrepareSessionRadiance(scene, lighting, options);
  const cv::Mat& floor = radiance.quads[0];
  // Texel (col, row) covers x = -2 + 4 (col + 0.5) / 32: under the box (x, y ~ 0) and at x = 1.
  const float under = floor.at<cv::Vec3f>(16, 16)[1];
  const float beside = floor.at<cv::Vec3f>(16, 24)[1];
  EXPECT_LT(under, 0.05f * beside) << under << " vs " << beside;
  EXPECT_GT(beside, 0.0f);
  // The box: its top vertices see the lamp, its bottom ones do not.
  const SceneMesh& box = scene.meshes[0];
  const std::vector<cv::Vec3f>& light = radiance.mesh_vertex_light[0];
  double top = 0.0, bottom = 0.0;
  for (size_t v = 0; v < light.size(); ++v) {
    if (box.normals_in_world[v].z() > 0.9f) top = std::max(top, static_cast<double>(light[v][1]));
    if (box.normals_in_world[v].z() < -0.9f) bottom = std::max(bottom, static_cast<double>(light[v][1]));
  }
  EXPECT_GT(top, 1.0);  // 100 cd at 1.1 m: ~83 lux, / pi
  EXPECT_EQ(bottom, 0.0);
  // Without the mesh the floor under it is lit.
  scene.SetMeshes({});
  EXPECT_GT(PrepareSessionRadiance(scene, lighting, options).quads[0].at<cv::Vec3f>(16, 16)[1], beside);
}

}  // namespace
}  // namespace duskmap
