#include "slam/synthetic/scene/furniture_layout.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>

#include "slam/core/check.h"
#include "slam/synthetic/assets/furniture_catalog.h"
#include "slam/synthetic/assets/furniture_placement.h"

namespace duskmap {

void FurnitureOptions::Check() const {
  SLAM_THROW_IF_NOT(ConfigError, max_edge_m >= 0.01 && max_edge_m <= 10.0)
      << "scene.furniture.max_edge_m must be in [0.01, 10], got " << max_edge_m;
  for (size_t i = 0; i < pieces.size(); ++i) {
    const FurniturePiece& p = pieces[i];
    const std::string where = "scene.furniture.pieces[" + std::to_string(i) + "]";
    SLAM_THROW_IF_NOT(ConfigError, !p.model.empty()) << where << ".model: empty";
    SLAM_THROW_IF_NOT(ConfigError, !p.room.empty()) << where << ".room: empty";
    SLAM_THROW_IF_NOT(ConfigError, p.position_m.allFinite())
        << where << ".position_m: not finite";
    SLAM_THROW_IF_NOT(ConfigError, std::isfinite(p.yaw_deg) && std::abs(p.yaw_deg) <= 360.0)
        << where << ".yaw_deg must be in [-360, 360], got " << p.yaw_deg;
    SLAM_THROW_IF_NOT(ConfigError, std::isfinite(p.elevation_m) && p.elevation_m >= 0.0 &&
                                       p.elevation_m <= 3.0)
        << where << ".elevation_m must be in [0, 3], got " << p.elevation_m;
  }
}

void AddFurniture(const FurnitureOptions& options, Scene* scene) {
  options.Check();
  if (options.pieces.empty()) return;
  const std::string path = options.catalog.empty() ? DefaultFurnitureCatalogPath() : options.catalog;
  const FurnitureCatalog catalog = FurnitureCatalog::Open(path);
  ObjLoadOptions load_options;
  // The CC-0 catalog's beds and technical tables name textures by absolute
  // Windows paths that are not in it; they keep their material colours.
  load_options.skip_unavailable_textures = true;
  SceneMeshOptions mesh_options;
  mesh_options.max_edge_m = options.max_edge_m;
  std::map<std::string, LoadedFurniture> loaded;  // by catalog id
  std::vector<SceneMesh> meshes = scene->meshes;
  for (size_t i = 0; i < options.pieces.size(); ++i) {
    const FurniturePiece& piece = options.pieces[i];
    const auto room = std::find(scene->room_names.begin(), scene->room_names.end(), piece.room);
    SLAM_THROW_IF_NOT(ConfigError, room != scene->room_names.end())
        << "scene.furniture.pieces[" << i << "].room: no room '" << piece.room << "'";
    const FurnitureEntry& entry = catalog.Find(piece.model);
    auto it = loaded.find(entry.id);
    if (it == loaded.end()) it = loaded.emplace(entry.id, LoadFurniture(catalog, entry, load_options)).first;
    const double yaw = piece.yaw_deg * M_PI / 180.0;
    const Rigid3d world_from_furniture(
        Eigen::Quaterniond(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ())),
        Eigen::Vector3d(piece.position_m.x(), piece.position_m.y(), piece.elevation_m));
    meshes.push_back(MakeSceneMesh(it->second.mesh_in_furniture, world_from_furniture,
                                   static_cast<int>(room - scene->room_names.begin()), entry.name,
                                   mesh_options));
    SceneMesh& mesh = meshes.back();
    mesh.catalog = std::filesystem::path(path).filename().string();
    mesh.model_id = entry.id;
    mesh.creator = entry.creator;
    mesh.license = entry.license;
  }
  scene->SetMeshes(std::move(meshes));
}

}  // namespace duskmap
