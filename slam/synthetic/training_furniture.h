// The furniture arrangement of a learned descriptor's training scene
// (training_scenes.h): the default arrangement's places
// (DefaultFurniturePieces(), off the patrol route and inside their rooms)
// each take a model of the CC0 catalog of the same group (seat, storage,
// bed, table, chair, floor object, object on a surface, wall item) whose
// footprint is at most 0.15 m wider and deeper than the default piece's,
// turned and moved a little: pieces against a wall stay against it (turned
// at most 4 degrees), the others move up to 0.15 m and turn up to 10 (tables)
// or 30 degrees; objects on a table, a bedside table or shelves ride on it at
// its new height. A fifth of the small pieces is left out. No piece comes
// closer to the patrol route than min(its default place's clearance, 0.3 m),
// leaves its room, or overlaps the floor pieces around it (drawn before it,
// default after it) more than the default piece did, plus 5 % of a
// footprint: chairs stay tucked at their table, not in it.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "slam/synthetic/scene/apartment.h"
#include "slam/synthetic/scene/furniture_layout.h"

namespace duskmap {

// A catalog model the training arrangements draw from, with its catalog size.
struct TrainingFurnitureModel {
  std::string group;  // "seat", "storage", "bed", "table", "chair", "floor", "surface", "wall"
  std::string model;  // id key in BlendSwap-CC-0.sh3f
  Eigen::Vector3d size_m = Eigen::Vector3d::Zero();  // width, depth, height (the catalog's, in metres)
};

// Every model the arrangements may draw (a model may be in two groups).
const std::vector<TrainingFurnitureModel>& TrainingFurnitureModels();

// The catalog size of `model` (width, depth, height, metres); SLAM_CHECKs
// that it is a model of TrainingFurnitureModels().
Eigen::Vector3d TrainingFurnitureSize(const std::string& model);

// Half the sides of the axis-aligned box around a piece's turned footprint (x, y).
Eigen::Vector2d FootprintHalfExtentsM(const FurniturePiece& piece, const Eigen::Vector3d& size_m);

// The shortest distance from a piece's turned footprint to the polyline
// through the route's waypoints (0 when they overlap), metres.
double RouteClearanceM(const FurniturePiece& piece, const Eigen::Vector3d& size_m,
                       const std::vector<RouteWaypoint>& route);

// The arrangement of one training scene, drawn from `seed`. Deterministic.
std::vector<FurniturePiece> DrawTrainingFurniture(uint64_t seed);

}  // namespace duskmap
