// Furnishes a scene with pieces of a furniture catalog (furniture_catalog.h):
// each piece is loaded once, placed at its catalog size
// (furniture_placement.h), turned and moved into the world and added as a
// SceneMesh of its room. The catalog is read at generation time from the
// installed package, never copied.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "slam/synthetic/scene/scene.h"

namespace duskmap {

struct FurniturePiece {
  std::string model;  // catalog id, id key ("bed1") or unique name
  std::string room;   // one of Scene::room_names
  Eigen::Vector2d position_m = Eigen::Vector2d::Zero();  // centre of the footprint, world x, y
  // Turn about z, counter-clockwise seen from above, degrees; 0 = the
  // piece's front faces south (-y), 90 = east, 180 = north, -90 = west.
  double yaw_deg = 0.0;
  double elevation_m = 0.0;  // base above the floor (a kettle on a worktop)
};

struct FurnitureOptions {
  std::string catalog;  // .sh3f file; "" = DefaultFurnitureCatalogPath()
  std::vector<FurniturePiece> pieces;  // none = no furniture meshes
  double max_edge_m = 0.12;            // SceneMeshOptions::max_edge_m

  void Check() const;  // throws ConfigError "scene.furniture...: problem"
};

// Adds the pieces to `scene` (Scene::SetMeshes), each with its catalog,
// id, creator and licence (SceneMesh). Throws InputError for a missing or corrupt catalog, a model
// absent from it and any error of its files (one line naming the file), and
// ConfigError for a room the scene does not have.
void AddFurniture(const FurnitureOptions& options, Scene* scene);

}  // namespace duskmap
