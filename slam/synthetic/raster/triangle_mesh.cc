#include "slam/synthetic/raster/triangle_mesh.h"

#include <set>

namespace duskmap {

Eigen::AlignedBox3d TriangleMesh::Bounds() const {
  Eigen::AlignedBox3d box;
  for (const MeshTriangle& triangle : triangles) {
    for (const int index : triangle.position) box.extend(positions[index].cast<double>());
  }
  return box;
}

int64_t TriangleMesh::TextureBytes() const {
  std::set<const uchar*> seen;
  int64_t bytes = 0;
  for (const Material& material : materials) {
    const cv::Mat& texture = material.diffuse_texture;
    if (texture.empty() || !seen.insert(texture.datastart).second) continue;
    bytes += static_cast<int64_t>(texture.total() * texture.elemSize());
  }
  return bytes;
}

}  // namespace duskmap
