// A textured triangle mesh, as loaded from an OBJ model (obj_mesh.h) and
// placed in the scene (furniture_placement.h). Colours are linear BGR, like
// Quad::albedo in scene.h.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <opencv2/core.hpp>

namespace duskmap {

struct Material {
  std::string name;  // the MTL's newmtl name ("" for faces that name no material)
  // Kd, linear BGR (the MTL's r g b reversed; exporters such as Blender write
  // linear colours, so they are taken as they are).
  cv::Vec3f diffuse_bgr = cv::Vec3f(0.8f, 0.8f, 0.8f);
  // map_Kd decoded to CV_32FC3 linear BGR in [0, 1] (from sRGB 8-bit), image
  // row 0 at the top, so texture coordinate v = 1 is row 0; empty when the
  // material has none (or it was skipped, ObjLoadOptions). Materials that name
  // the same image share its pixels.
  cv::Mat diffuse_texture;
  std::string diffuse_texture_path;  // archive path of map_Kd, "" when none
  // map_Kd's -s and -o: texture coordinates used are offset + scale * (u, v).
  Eigen::Vector2f texture_scale = Eigen::Vector2f::Ones();
  Eigen::Vector2f texture_offset = Eigen::Vector2f::Zero();
  // Opacity: d, or 1 - Tr; nullopt when the MTL gives neither (opaque).
  std::optional<float> dissolve;
};

struct MeshTriangle {
  std::array<int, 3> position = {0, 0, 0};     // into TriangleMesh::positions, counter-clockwise seen from the front
  std::array<int, 3> texcoord = {-1, -1, -1};  // into texcoords, -1 = none
  std::array<int, 3> normal = {-1, -1, -1};    // into normals, -1 = none
  int material = 0;                            // into materials
  int part = -1;                               // into part_names (the OBJ's last g or o), -1 = none
  int smoothing_group = 0;                     // the OBJ's s, 0 = off
};

struct TriangleMesh {
  // Vertex positions: in the OBJ's own frame and units as loaded; in metres
  // in the furniture frame once placed (furniture_placement.h).
  std::vector<Eigen::Vector3f> positions;
  std::vector<Eigen::Vector2f> texcoords;  // (u, v), v = 0 at the image's bottom row
  std::vector<Eigen::Vector3f> normals;    // unit
  std::vector<MeshTriangle> triangles;
  std::vector<Material> materials;
  std::vector<std::string> part_names;

  // The box around the vertices the triangles use (empty when none).
  Eigen::AlignedBox3d Bounds() const;
  // Bytes of the decoded textures, each image counted once.
  int64_t TextureBytes() const;
};

}  // namespace duskmap
