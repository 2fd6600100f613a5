// A furniture mesh placed in the world, in the form the lighting and the
// renderer use: vertices (a position with one shading normal and one texture
// coordinate) in the world frame, triangles over them with a material each,
// textures mip-mapped. Edges longer than SceneMeshOptions::max_edge_m are
// split, so that the per-vertex lighting (lighting.h) resolves cast shadows
// and lamp pools on large faces; an edge's split depends on the edge alone,
// so two triangles sharing it split it alike and no crack opens.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include "slam/core/rigid3.h"
#include "slam/synthetic/raster/mip_texture.h"
#include "slam/synthetic/raster/triangle_bvh.h"
#include "slam/synthetic/raster/triangle_mesh.h"

namespace duskmap {

struct SceneMaterial {
  cv::Vec3f diffuse_bgr = cv::Vec3f(0.8f, 0.8f, 0.8f);  // Kd, linear; multiplies the texture
  std::shared_ptr<const MipTexture> texture;            // map_Kd; null = Kd alone
  Eigen::Vector2f texture_scale = Eigen::Vector2f::Ones();  // uv used = offset + scale * uv
  Eigen::Vector2f texture_offset = Eigen::Vector2f::Zero();
};

struct SceneMeshOptions {
  double max_edge_m = 0.12;      // longer edges are split (lighting resolution)
  int max_triangles = 400000;    // per piece after splitting; more is an InputError

  void Check() const;  // throws ConfigError naming the field
};

struct SceneMesh {
  std::string name;  // the catalog piece, e.g. "Bed"
  // Where it comes from, for the dataset's manifest: the catalog's file
  // name and id#N, the model's creator and licence.
  std::string catalog;
  std::string model_id;
  std::string creator;
  std::string license;
  int room = 0;      // index into Scene::room_names: the light that reaches it
  std::vector<Eigen::Vector3f> positions_in_world;
  std::vector<Eigen::Vector3f> normals_in_world;  // unit, per vertex
  std::vector<Eigen::Vector2f> texcoords;         // per vertex, (0, 0) without texture coordinates
  std::vector<std::array<int, 3>> triangles;      // counter-clockwise seen from the front
  std::vector<int> triangle_material;             // per triangle, into materials
  std::vector<SceneMaterial> materials;
  Eigen::AlignedBox3d bounds_in_world;
};

// Places `mesh_in_furniture` (furniture_placement.h) at world_from_furniture
// in `room`. Vertices are shared where the OBJ shares position, normal and
// texture coordinates; a corner without a normal takes its face's. Throws
// InputError naming `name` when splitting would exceed max_triangles.
SceneMesh MakeSceneMesh(const TriangleMesh& mesh_in_furniture, const Rigid3d& world_from_furniture,
                        int room, const std::string& name, const SceneMeshOptions& options = {});

// The world triangles of all meshes, in order (mesh 0's first), for shadow rays.
TriangleBvh BuildMeshOccluders(const std::vector<SceneMesh>& meshes);

}  // namespace duskmap
