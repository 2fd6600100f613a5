// Places a furniture catalog's model the way SweetHome3D shows it, in the
// furniture frame the apartment then puts it in with a world_from_furniture
// transform (a turn about z and a translation).
//
// Furniture frame: metres, x = the piece's width (east when unturned),
// y = its depth (north), z = its height (up); its front faces -y (south);
// the bounding box centred on the origin in x and y, its base on z = 0.
//
// From the OBJ (SweetHome3D's model frame: y up, the front towards +z, any
// units), as SweetHome3D's ModelManager does: turn by modelRotation
// (p_r = R p), scale the box around p_r to width x height x depth along
// x, y, z (centimetres / 100), centre it; then x_f = x, y_f = -z,
// z_f = y - min y. An axis along which the model is flat is not scaled.
// Normals follow (inverse transpose of the scaling, renormalised).
#pragma once

#include <string>

#include <Eigen/Core>

#include "slam/synthetic/assets/furniture_catalog.h"
#include "slam/synthetic/assets/obj_mesh.h"
#include "slam/synthetic/raster/triangle_mesh.h"

namespace duskmap {

// The rotation furniture_from_model_scaled: from SweetHome3D's model axes
// (x right, y up, z front) to the furniture frame (x, -z, y).
Eigen::Matrix3d FurnitureFromSweetHome3dAxes();

// `mesh_in_model` (an OBJ as loaded) placed in the furniture frame at
// `entry`'s size_cm and model_rotation. Throws InputError naming the entry's
// model when the mesh has no triangles.
TriangleMesh PlaceFurnitureModel(TriangleMesh mesh_in_model, const FurnitureEntry& entry);

struct LoadedFurniture {
  FurnitureEntry entry;
  TriangleMesh mesh_in_furniture;  // placed: metres, furniture frame
  ObjLoadResult load;              // the OBJ load's counts and skipped textures (its mesh moved out)
};

// Loads `entry`'s model from `catalog` and places it.
LoadedFurniture LoadFurniture(const FurnitureCatalog& catalog, const FurnitureEntry& entry,
                              const ObjLoadOptions& options = {});

}  // namespace duskmap
