#include "slam/synthetic/assets/furniture_placement.h"

#include <Eigen/Dense>

#include "slam/core/check.h"

namespace duskmap {
namespace {

// Extents below this (in the OBJ's units) count as flat: not scaled.
constexpr double kFlatExtent = 1e-9;

}  // namespace

Eigen::Matrix3d FurnitureFromSweetHome3dAxes() {
  Eigen::Matrix3d rotation;
  rotation << 1, 0, 0,  //
      0, 0, -1,         //
      0, 1, 0;
  return rotation;
}

TriangleMesh PlaceFurnitureModel(TriangleMesh mesh_in_model, const FurnitureEntry& entry) {
  SLAM_THROW_IF_NOT(InputError, !mesh_in_model.triangles.empty())
      << entry.model_path << ": no triangles to place (entry #" << entry.index << " '" << entry.name << "')";
  const Eigen::Matrix3d rotation = entry.model_rotation.value_or(Eigen::Matrix3d::Identity());
  Eigen::AlignedBox3d box;
  for (const MeshTriangle& triangle : mesh_in_model.triangles) {
    for (const int index : triangle.position) box.extend(rotation * mesh_in_model.positions[index].cast<double>());
  }
  // SweetHome3D's model axes: width along x, height along y, depth along z.
  const Eigen::Vector3d target_m = Eigen::Vector3d(entry.size_cm.x(), entry.size_cm.z(), entry.size_cm.y()) / 100.0;
  const Eigen::Vector3d extent = box.sizes();
  Eigen::Vector3d scale = Eigen::Vector3d::Ones();
  for (int k = 0; k < 3; ++k) {
    if (extent[k] > kFlatExtent) scale[k] = target_m[k] / extent[k];
  }
  // p_f = axes * (scale .* (R p - centre)) + (0, 0, height / 2)
  const Eigen::Matrix3d axes = FurnitureFromSweetHome3dAxes();
  const Eigen::Matrix3d linear = axes * scale.asDiagonal() * rotation;
  const Eigen::Vector3d lift(0, 0, 0.5 * scale.y() * extent.y());
  const Eigen::Vector3d offset = lift - axes * scale.asDiagonal() * box.center();
  const Eigen::Matrix3d normal_linear = axes * scale.cwiseInverse().asDiagonal() * rotation;

  TriangleMesh placed = std::move(mesh_in_model);
  for (Eigen::Vector3f& p : placed.positions) p = (linear * p.cast<double>() + offset).cast<float>();
  for (Eigen::Vector3f& n : placed.normals) {
    const Eigen::Vector3d turned = normal_linear * n.cast<double>();
    n = (turned.norm() > 0 ? turned.normalized() : turned).cast<float>();
  }
  return placed;
}

LoadedFurniture LoadFurniture(const FurnitureCatalog& catalog, const FurnitureEntry& entry,
                              const ObjLoadOptions& options) {
  LoadedFurniture loaded;
  loaded.entry = entry;
  loaded.load = LoadObjMesh(entry.model_path, catalog.Files(), options);
  loaded.mesh_in_furniture = PlaceFurnitureModel(std::move(loaded.load.mesh), entry);
  loaded.load.mesh = TriangleMesh();
  return loaded;
}

}  // namespace duskmap
