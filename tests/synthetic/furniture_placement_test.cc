#include "slam/synthetic/assets/furniture_placement.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "mesh_test_files.h"
#include "slam/core/check.h"

namespace duskmap {
namespace {

// A box model in SweetHome3D's axes and arbitrary units, x in [0, 2],
// y (up) in [1, 2], z in [-4, 0], with a marker triangle on its front
// (+z) face and a slanted top face for the normals.
TriangleMesh BoxModel() {
  TriangleMesh mesh;
  for (const double x : {0.0, 2.0}) {
    for (const double y : {1.0, 2.0}) {
      for (const double z : {-4.0, 0.0}) mesh.positions.emplace_back(x, y, z);
    }
  }
  // corners: index = 4 * (x == 2) + 2 * (y == 2) + (z == 0)
  const std::vector<std::array<int, 3>> faces = {{0, 2, 6}, {1, 5, 7}, {0, 4, 5}};
  for (const auto& face : faces) {
    MeshTriangle triangle;
    triangle.position = face;
    mesh.triangles.push_back(triangle);
  }
  mesh.materials.emplace_back();
  return mesh;
}

FurnitureEntry Entry(double width_cm, double depth_cm, double height_cm) {
  FurnitureEntry entry;
  entry.index = 7;
  entry.name = "Box";
  entry.model_path = "models/box.obj";
  entry.size_cm = Eigen::Vector3d(width_cm, depth_cm, height_cm);
  return entry;
}

void ExpectBox(const Eigen::AlignedBox3d& box, const Eigen::Vector3d& min, const Eigen::Vector3d& max) {
  EXPECT_TRUE(box.min().isApprox(min, 1e-6)) << box.min().transpose() << " vs " << min.transpose();
  EXPECT_TRUE(box.max().isApprox(max, 1e-6)) << box.max().transpose() << " vs " << max.transpose();
}

TEST(FurnitureFromSweetHome3dAxes, IsARightHandedRotationYUpToZUp) {
  const Eigen::Matrix3d r = FurnitureFromSweetHome3dAxes();
  EXPECT_TRUE((r.transpose() * r).isIdentity(1e-12));
  EXPECT_DOUBLE_EQ(r.determinant(), 1.0);
  EXPECT_TRUE((r * Eigen::Vector3d::UnitX()).isApprox(Eigen::Vector3d::UnitX()));   // width stays east
  EXPECT_TRUE((r * Eigen::Vector3d::UnitY()).isApprox(Eigen::Vector3d::UnitZ()));   // up
  EXPECT_TRUE((r * Eigen::Vector3d::UnitZ()).isApprox(-Eigen::Vector3d::UnitY()));  // the front faces south
}

TEST(PlaceFurnitureModel, ScalesToTheCatalogSizeCentredWithItsBaseOnTheFloor) {
  const TriangleMesh placed = PlaceFurnitureModel(BoxModel(), Entry(100, 50, 30));
  ExpectBox(placed.Bounds(), Eigen::Vector3d(-0.5, -0.25, 0), Eigen::Vector3d(0.5, 0.25, 0.3));
  // OBJ corner (x = 2, y = 2, z = 0): right, top, front -> east, up, south.
  EXPECT_TRUE(placed.positions[7].cast<double>().isApprox(Eigen::Vector3d(0.5, -0.25, 0.3), 1e-6));
  // OBJ corner (0, 1, -4): left, bottom, back -> west, floor, north.
  EXPECT_TRUE(placed.positions[0].cast<double>().isApprox(Eigen::Vector3d(-0.5, 0.25, 0), 1e-6));
}

TEST(PlaceFurnitureModel, TurnsByTheModelRotationFirst) {
  // A model made z-up (as in a modeller): its height along OBJ z. The
  // rotation (x, y, z) -> (x, z, -y), catalog entry #70's, stands it up.
  TriangleMesh model = BoxModel();
  for (Eigen::Vector3f& p : model.positions) p = Eigen::Vector3f(p.x(), -p.z(), p.y());
  FurnitureEntry entry = Entry(100, 50, 30);
  Eigen::Matrix3d rotation;
  rotation << 1, 0, 0, 0, 0, 1, 0, -1, 0;
  entry.model_rotation = rotation;
  const TriangleMesh placed = PlaceFurnitureModel(model, entry);
  ExpectBox(placed.Bounds(), Eigen::Vector3d(-0.5, -0.25, 0), Eigen::Vector3d(0.5, 0.25, 0.3));
  EXPECT_TRUE(placed.positions[7].cast<double>().isApprox(Eigen::Vector3d(0.5, -0.25, 0.3), 1e-6));
}

TEST(PlaceFurnitureModel, NormalsStayPerpendicularToTheirTrianglesUnderUnevenScaling) {
  TriangleMesh model = BoxModel();
  // A slanted triangle with its normal.
  model.positions.emplace_back(0, 1, 0);
  model.positions.emplace_back(2, 2, 0);
  model.positions.emplace_back(0, 2, -4);
  const int base = static_cast<int>(model.positions.size()) - 3;
  const Eigen::Vector3f a = model.positions[base], b = model.positions[base + 1], c = model.positions[base + 2];
  model.normals.push_back((b - a).cross(c - a).normalized());
  MeshTriangle slanted;
  slanted.position = {base, base + 1, base + 2};
  slanted.normal = {0, 0, 0};
  model.triangles.push_back(slanted);
  const TriangleMesh placed = PlaceFurnitureModel(model, Entry(300, 20, 90));
  const Eigen::Vector3f pa = placed.positions[base], pb = placed.positions[base + 1], pc = placed.positions[base + 2];
  const Eigen::Vector3f n = placed.normals[0];
  EXPECT_NEAR(n.norm(), 1.0f, 1e-6);
  EXPECT_NEAR(n.dot((pb - pa).normalized()), 0.0f, 1e-6);
  EXPECT_NEAR(n.dot((pc - pa).normalized()), 0.0f, 1e-6);
  EXPECT_GT(n.dot((pb - pa).cross(pc - pa)), 0.0f);  // still on the counter-clockwise side
}

TEST(PlaceFurnitureModel, LeavesAFlatAxisUnscaled) {
  TriangleMesh model;
  model.positions = {Eigen::Vector3f(0, 0, 0), Eigen::Vector3f(4, 0, 0), Eigen::Vector3f(4, 0, 2)};
  model.triangles.resize(1);
  model.triangles[0].position = {0, 1, 2};
  model.materials.emplace_back();
  const TriangleMesh placed = PlaceFurnitureModel(model, Entry(80, 40, 10));  // a rug: no height in the model
  ExpectBox(placed.Bounds(), Eigen::Vector3d(-0.4, -0.2, 0), Eigen::Vector3d(0.4, 0.2, 0));
  for (const Eigen::Vector3f& p : placed.positions) EXPECT_TRUE(p.allFinite());
}

TEST(PlaceFurnitureModel, RefusesAMeshWithoutTriangles) {
  EXPECT_EQ(InputErrorOf([] { PlaceFurnitureModel(TriangleMesh(), Entry(1, 1, 1)); }),
            "models/box.obj: no triangles to place (entry #7 'Box')");
}

}  // namespace
}  // namespace duskmap
