#include "slam/synthetic/scene/scene_mesh.h"

#include <algorithm>
#include <map>
#include <tuple>
#include <utility>

#include "slam/core/check.h"

namespace duskmap {
namespace {

struct Vertex {
  Eigen::Vector3f position;
  Eigen::Vector3f normal;
  Eigen::Vector2f texcoord;
};

// Builds the vertices and triangles, splitting long edges. A midpoint is
// shared by the triangles that share the edge's two vertices.
class Splitter {
 public:
  Splitter(double max_edge_m, int max_triangles, const std::string& name)
      : max_edge_sq_(static_cast<float>(max_edge_m * max_edge_m)),
        max_triangles_(max_triangles),
        name_(name) {}

  int AddVertex(const Vertex& v) {
    vertices_.push_back(v);
    return static_cast<int>(vertices_.size()) - 1;
  }

  void AddTriangle(std::array<int, 3> t, int material) {
    std::vector<std::array<int, 3>> work = {t};
    while (!work.empty()) {
      const std::array<int, 3> tri = work.back();
      work.pop_back();
      bool split[3];
      int count = 0;
      for (int e = 0; e < 3; ++e) {
        split[e] = Long(tri[e], tri[(e + 1) % 3]);
        count += split[e];
      }
      if (count == 0) {
        SLAM_THROW_IF_NOT(InputError, static_cast<int>(triangles_.size()) < max_triangles_)
            << name_ << ": more than " << max_triangles_
            << " triangles after splitting long edges (raise max_triangles or max_edge_m)";
        triangles_.push_back(tri);
        materials_.push_back(material);
        continue;
      }
      // Rotate so that the pattern starts at edge 0.
      int first = 0;
      if (count == 1) {
        while (!split[first]) ++first;
      } else if (count == 2) {
        while (split[first]) ++first;  // the edge not split
        first = (first + 1) % 3;       // the split edges are first, first + 1
      }
      const int a = tri[first], b = tri[(first + 1) % 3], c = tri[(first + 2) % 3];
      if (count == 1) {
        const int ab = Midpoint(a, b);
        work.push_back({a, ab, c});
        work.push_back({ab, b, c});
      } else if (count == 2) {
        const int ab = Midpoint(a, b), bc = Midpoint(b, c);
        work.push_back({ab, b, bc});
        // The quadrilateral a, ab, bc, c, cut along its shorter diagonal.
        if (DistanceSq(a, bc) <= DistanceSq(ab, c)) {
          work.push_back({a, ab, bc});
          work.push_back({a, bc, c});
        } else {
          work.push_back({a, ab, c});
          work.push_back({ab, bc, c});
        }
      } else {
        const int ab = Midpoint(a, b), bc = Midpoint(b, c), ca = Midpoint(c, a);
        work.push_back({a, ab, ca});
        work.push_back({ab, b, bc});
        work.push_back({ca, bc, c});
        work.push_back({ab, bc, ca});
      }
    }
  }

  std::vector<Vertex>& vertices() { return vertices_; }
  std::vector<std::array<int, 3>>& triangles() { return triangles_; }
  std::vector<int>& materials() { return materials_; }

 private:
  float DistanceSq(int a, int b) const {
    return (vertices_[a].position - vertices_[b].position).squaredNorm();
  }
  bool Long(int a, int b) const { return DistanceSq(a, b) > max_edge_sq_; }

  int Midpoint(int a, int b) {
    const std::pair<int, int> key = std::minmax(a, b);
    const auto it = midpoints_.find(key);
    if (it != midpoints_.end()) return it->second;
    const Vertex& va = vertices_[key.first];
    const Vertex& vb = vertices_[key.second];
    Vertex m;
    // (p + q) * 0.5 is symmetric in p and q: a neighbour whose own vertices
    // sit at the same positions computes the same midpoint.
    m.position = (va.position + vb.position) * 0.5f;
    const Eigen::Vector3f n = va.normal + vb.normal;
    m.normal = n.squaredNorm() > 1e-12f ? n.normalized() : va.normal;
    m.texcoord = (va.texcoord + vb.texcoord) * 0.5f;
    const int index = AddVertex(m);
    midpoints_.emplace(key, index);
    return index;
  }

  float max_edge_sq_;
  int max_triangles_;
  std::string name_;
  std::vector<Vertex> vertices_;
  std::vector<std::array<int, 3>> triangles_;
  std::vector<int> materials_;
  std::map<std::pair<int, int>, int> midpoints_;
};

}  // namespace

void SceneMeshOptions::Check() const {
  SLAM_THROW_IF_NOT(ConfigError, max_edge_m >= 0.01)
      << "SceneMeshOptions.max_edge_m must be >= 0.01, got " << max_edge_m;
  SLAM_THROW_IF_NOT(ConfigError, max_triangles >= 1)
      << "SceneMeshOptions.max_triangles must be >= 1, got " << max_triangles;
}

SceneMesh MakeSceneMesh(const TriangleMesh& mesh, const Rigid3d& world_from_furniture, int room,
                        const std::string& name, const SceneMeshOptions& options) {
  options.Check();
  SceneMesh out;
  out.name = name;
  out.room = room;
  const Eigen::Matrix3f rotation =
      world_from_furniture.rotation.toRotationMatrix().cast<float>();
  const Eigen::Vector3f translation = world_from_furniture.translation.cast<float>();
  std::vector<Eigen::Vector3f> positions(mesh.positions.size());
  for (size_t i = 0; i < positions.size(); ++i) {
    positions[i] = rotation * mesh.positions[i] + translation;
  }
  Splitter splitter(options.max_edge_m, options.max_triangles, name);
  // (position, normal or -1, texcoord, the face normal when -1) -> vertex:
  // corners without a normal share a vertex with coplanar neighbours.
  std::map<std::tuple<int, int, int, float, float, float>, int> shared;
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    const MeshTriangle& tri = mesh.triangles[t];
    const Eigen::Vector3f face = (positions[tri.position[1]] - positions[tri.position[0]])
                                     .cross(positions[tri.position[2]] - positions[tri.position[0]]);
    if (face.squaredNorm() <= 0.0f) continue;  // degenerate: covers nothing, lights nothing
    const Eigen::Vector3f face_normal = face.normalized();
    std::array<int, 3> corners;
    for (int k = 0; k < 3; ++k) {
      const int n = tri.normal[k];
      const bool own = n >= 0;
      const std::tuple<int, int, int, float, float, float> key(
          tri.position[k], own ? n : -1, tri.texcoord[k], own ? 0.0f : face_normal.x(),
          own ? 0.0f : face_normal.y(), own ? 0.0f : face_normal.z());
      const auto it = shared.find(key);
      if (it != shared.end()) {
        corners[k] = it->second;
        continue;
      }
      Vertex v;
      v.position = positions[tri.position[k]];
      v.normal = n >= 0 ? Eigen::Vector3f(rotation * mesh.normals[n]) : face_normal;
      if (v.normal.squaredNorm() < 1e-12f) v.normal = face_normal;
      v.normal.normalize();
      v.texcoord = tri.texcoord[k] >= 0 ? mesh.texcoords[tri.texcoord[k]] : Eigen::Vector2f::Zero();
      corners[k] = splitter.AddVertex(v);
      shared.emplace(key, corners[k]);
    }
    splitter.AddTriangle(corners, tri.material);
  }
  for (const Vertex& v : splitter.vertices()) {
    out.positions_in_world.push_back(v.position);
    out.normals_in_world.push_back(v.normal);
    out.texcoords.push_back(v.texcoord);
    out.bounds_in_world.extend(v.position.cast<double>());
  }
  out.triangles = std::move(splitter.triangles());
  out.triangle_material = std::move(splitter.materials());
  // Materials: one mip pyramid per distinct image (materials may share one).
  std::map<const void*, std::shared_ptr<const MipTexture>> pyramids;
  for (const Material& m : mesh.materials) {
    SceneMaterial s;
    s.diffuse_bgr = m.diffuse_bgr;
    s.texture_scale = m.texture_scale;
    s.texture_offset = m.texture_offset;
    if (!m.diffuse_texture.empty()) {
      auto& pyramid = pyramids[m.diffuse_texture.data];
      if (!pyramid) pyramid = std::make_shared<const MipTexture>(m.diffuse_texture);
      s.texture = pyramid;
    }
    out.materials.push_back(s);
  }
  if (out.materials.empty()) out.materials.push_back(SceneMaterial());
  for (int& m : out.triangle_material) {
    if (m < 0 || m >= static_cast<int>(out.materials.size())) m = 0;
  }
  return out;
}

TriangleBvh BuildMeshOccluders(const std::vector<SceneMesh>& meshes) {
  std::vector<WorldTriangle> triangles;
  for (const SceneMesh& mesh : meshes) {
    for (const std::array<int, 3>& t : mesh.triangles) {
      triangles.push_back({mesh.positions_in_world[t[0]], mesh.positions_in_world[t[1]],
                           mesh.positions_in_world[t[2]]});
    }
  }
  return TriangleBvh(triangles);
}

}  // namespace duskmap
