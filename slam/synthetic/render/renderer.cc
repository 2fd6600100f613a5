#include "slam/synthetic/render/renderer.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "slam/core/check.h"
#include "slam/synthetic/raster/mip_texture.h"
#include "slam/synthetic/raster/triangle_raster.h"

namespace duskmap {

struct Renderer::QuadSetup {
  int index = -1;
  Eigen::Vector2d polygon[8];  // clipped, projected vertices (pixels)
  int count = 0;
  // inv_depth = a*u + b*v + c
  double inv_a = 0, inv_b = 0, inv_c = 0;
  // texel x = (sa*u + sb*v + sc) / inv_depth + sd, same for y with t*.
  double sa = 0, sb = 0, sc = 0, sd = 0;
  double ta = 0, tb = 0, tc = 0, td = 0;
  double cos_a = 0, cos_b = 0, cos_c = 0;  // n . d (unnormalised ray)
};

namespace {

// Texture access without going through cv::Mat per pixel.
struct Texture {
  const uint8_t* data;
  size_t step;
  int max_x, max_y;
};

std::vector<Texture> TexturesOf(const std::vector<cv::Mat>& radiance) {
  std::vector<Texture> textures(radiance.size());
  for (size_t i = 0; i < radiance.size(); ++i) {
    SLAM_CHECK(radiance[i].type() == CV_32FC3 && !radiance[i].empty());
    textures[i] = {radiance[i].data, radiance[i].step[0], radiance[i].cols - 1,
                   radiance[i].rows - 1};
  }
  return textures;
}

}  // namespace

Renderer::Renderer(const Scene& scene, const PinholeCamera& camera, double near_m)
    : scene_(scene), camera_(camera), near_m_(near_m) {
  SLAM_CHECK(camera_.IsValid());
  for (const Quad& q : scene_.quads) has_mirrors_ |= q.mirror_reflectance > 0.0;
}

bool Renderer::SetupQuad(const Quad& q, int index, const Rigid3d& camera_from_world,
                         bool mirrored, QuadSetup* s) const {
  const Eigen::Matrix3d r = camera_from_world.rotation.toRotationMatrix();
  const Eigen::Vector3d o = camera_from_world * q.origin_in_world;
  const Eigen::Vector3d u = r * q.u_axis, v = r * q.v_axis, n = u.cross(v);
  const double k = n.dot(o);  // the plane n . x = k (camera frame)
  // Back face or edge-on (a mirror image shows the side its normal turns away).
  if ((mirrored ? -k : k) >= -1e-9) return false;
  const Eigen::Vector3d corners[4] = {o, o + u * q.size_u_m, o + u * q.size_u_m + v * q.size_v_m,
                                      o + v * q.size_v_m};
  s->count = 0;
  for (int i = 0; i < 4; ++i) {
    const Eigen::Vector3d& a = corners[i];
    const Eigen::Vector3d& b = corners[(i + 1) % 4];
    if (a.z() >= near_m_) s->polygon[s->count++] = Eigen::Vector2d(camera_.fx * a.x() / a.z() + camera_.cx, camera_.fy * a.y() / a.z() + camera_.cy);
    if ((a.z() >= near_m_) != (b.z() >= near_m_)) {
      const Eigen::Vector3d p = a + (b - a) * ((near_m_ - a.z()) / (b.z() - a.z()));
      s->polygon[s->count++] = Eigen::Vector2d(camera_.fx * p.x() / p.z() + camera_.cx, camera_.fy * p.y() / p.z() + camera_.cy);
    }
  }
  if (s->count < 3) return false;
  s->index = index;
  const double ifx = 1.0 / camera_.fx, ify = 1.0 / camera_.fy;
  // d(u, v) = ((u - cx)/fx, (v - cy)/fy, 1): a dot product with d is affine in (u, v).
  auto affine = [&](const Eigen::Vector3d& w, double* a, double* b, double* c) {
    *a = w.x() * ifx;
    *b = w.y() * ify;
    *c = w.z() - w.x() * camera_.cx * ifx - w.y() * camera_.cy * ify;
  };
  affine(n / k, &s->inv_a, &s->inv_b, &s->inv_c);
  affine(n, &s->cos_a, &s->cos_b, &s->cos_c);
  const double scale_s = q.albedo.cols / q.size_u_m, scale_t = q.albedo.rows / q.size_v_m;
  affine(u * scale_s, &s->sa, &s->sb, &s->sc);
  s->sd = -u.dot(o) * scale_s - 0.5;
  affine(v * scale_t, &s->ta, &s->tb, &s->tc);
  s->td = -v.dot(o) * scale_t - 0.5;
  return true;
}

void Renderer::RasterizeDepth(const QuadSetup& s, cv::Mat* inv_depth, cv::Mat* ids,
                              const MirrorMask* mask) const {
  double y_min = 1e30, y_max = -1e30;
  for (int i = 0; i < s.count; ++i) {
    y_min = std::min(y_min, s.polygon[i].y());
    y_max = std::max(y_max, s.polygon[i].y());
  }
  const int row_begin = std::max(0, static_cast<int>(std::ceil(y_min)));
  const int row_end = std::min(camera_.height - 1, static_cast<int>(std::floor(y_max)));
  for (int row = row_begin; row <= row_end; ++row) {
    double x_lo = 1e30, x_hi = -1e30;
    for (int i = 0; i < s.count; ++i) {
      const Eigen::Vector2d& a = s.polygon[i];
      const Eigen::Vector2d& b = s.polygon[(i + 1) % s.count];
      if ((a.y() <= row && b.y() >= row) || (b.y() <= row && a.y() >= row)) {
        const double x = std::abs(b.y() - a.y()) < 1e-12 ? std::min(a.x(), b.x()) : a.x() + (row - a.y()) * (b.x() - a.x()) / (b.y() - a.y());
        const double x2 = std::abs(b.y() - a.y()) < 1e-12 ? std::max(a.x(), b.x()) : x;
        x_lo = std::min(x_lo, x);
        x_hi = std::max(x_hi, x2);
      }
    }
    const int col_begin = std::max(0, static_cast<int>(std::ceil(x_lo)));
    const int col_end = std::min(camera_.width - 1, static_cast<int>(std::floor(x_hi)));
    float* depth_row = inv_depth->ptr<float>(row);
    int* id_row = ids->ptr<int>(row);
    const int* mirror_ids = mask ? mask->ids->ptr<int>(row) : nullptr;
    const float* mirror_depth = mask ? mask->depth_m->ptr<float>(row) : nullptr;
    double inv = s.inv_a * col_begin + s.inv_b * row + s.inv_c;
    for (int col = col_begin; col <= col_end; ++col, inv += s.inv_a) {
      if (mask && (mirror_ids[col] != mask->mirror || inv * mirror_depth[col] >= 1.0)) continue;
      if (inv > depth_row[col]) {
        depth_row[col] = static_cast<float>(inv);
        id_row[col] = s.index;
      }
    }
  }
}

namespace {

// The bilinear, perspective-correct radiance of quad setup s at pixel
// (col, row), whose depth is z.
template <typename Setup>
void Sample(const Setup& s, const Texture& t, int col, int row, double z, float* out) {
  const double x = (s.sa * col + s.sb * row + s.sc) * z + s.sd;
  const double y = (s.ta * col + s.tb * row + s.tc) * z + s.td;
  const int x0 = std::clamp(static_cast<int>(std::floor(x)), 0, t.max_x);
  const int y0 = std::clamp(static_cast<int>(std::floor(y)), 0, t.max_y);
  const int x1 = std::min(x0 + 1, t.max_x), y1 = std::min(y0 + 1, t.max_y);
  const float fx = static_cast<float>(std::clamp(x - x0, 0.0, 1.0));
  const float fy = static_cast<float>(std::clamp(y - y0, 0.0, 1.0));
  const float* r0 = reinterpret_cast<const float*>(t.data + y0 * t.step);
  const float* r1 = reinterpret_cast<const float*>(t.data + y1 * t.step);
  const float w00 = (1 - fx) * (1 - fy), w01 = fx * (1 - fy), w10 = (1 - fx) * fy, w11 = fx * fy;
  for (int k = 0; k < 3; ++k) {
    out[k] = r0[3 * x0 + k] * w00 + r0[3 * x1 + k] * w01 + r1[3 * x0 + k] * w10 + r1[3 * x1 + k] * w11;
  }
}

}  // namespace

void Renderer::AddReflection(int mirror, const std::vector<cv::Mat>& radiance,
                             const Rigid3d& camera_from_world, RenderedView* view) const {
  const Quad& glass = scene_.quads[mirror];
  const Eigen::Vector3d n = glass.normal();  // towards the room
  const Eigen::Vector3d& p0 = glass.origin_in_world;
  auto point = [&](const Eigen::Vector3d& x) -> Eigen::Vector3d {
    return x - 2.0 * (x - p0).dot(n) * n;
  };
  auto direction = [&](const Eigen::Vector3d& d) -> Eigen::Vector3d {
    return d - 2.0 * d.dot(n) * n;
  };
  const cv::Size size(camera_.width, camera_.height);
  cv::Mat mirror_inv_depth(size, CV_32FC1, cv::Scalar(0.0f));
  cv::Mat mirror_ids(size, CV_32SC1, cv::Scalar(-1));
  const MirrorMask mask{&view->surface_id, &view->depth_m, mirror};
  std::vector<QuadSetup> setups(scene_.quads.size());
  for (size_t i = 0; i < scene_.quads.size(); ++i) {
    const Quad& q = scene_.quads[i];
    if (static_cast<int>(i) == mirror) continue;
    // Only what is on the room's side of the glass is reflected.
    bool room_side = false;
    for (double s : {0.0, q.size_u_m}) {
      for (double t : {0.0, q.size_v_m}) room_side |= (q.PointAt(s, t) - p0).dot(n) > 0.0;
    }
    if (!room_side) continue;
    Quad image = q;
    image.origin_in_world = point(q.origin_in_world);
    image.u_axis = direction(q.u_axis);
    image.v_axis = direction(q.v_axis);
    if (SetupQuad(image, static_cast<int>(i), camera_from_world, true, &setups[i])) {
      RasterizeDepth(setups[i], &mirror_inv_depth, &mirror_ids, &mask);
    }
  }
  const std::vector<Texture> textures = TexturesOf(radiance);
  const double r0 = glass.mirror_reflectance;
  for (int row = 0; row < size.height; ++row) {
    const int* id_row = mirror_ids.ptr<int>(row);
    const float* inv_row = mirror_inv_depth.ptr<float>(row);
    const float* cos_row = view->cos_incidence.ptr<float>(row);
    float* out = view->radiance.ptr<float>(row);
    for (int col = 0; col < size.width; ++col) {
      const int id = id_row[col];
      if (id < 0) continue;
      float reflected[3];
      Sample(setups[id], textures[id], col, row, 1.0 / inv_row[col], reflected);
      // Schlick's approximation of the Fresnel reflectance.
      const double c = 1.0 - std::clamp(static_cast<double>(cos_row[col]), 0.0, 1.0);
      const float fresnel = static_cast<float>(r0 + (1.0 - r0) * c * c * c * c * c);
      for (int k = 0; k < 3; ++k) {
        out[3 * col + k] = (1.0f - fresnel) * out[3 * col + k] + fresnel * reflected[k];
      }
    }
  }
}

namespace {

// The meshes' triangles drawn into a shared depth buffer: the winning
// triangle's id (first_id[m] + its index in mesh m) and barycentrics per
// pixel, and each drawn mesh's vertices in the camera frame.
struct MeshRaster {
  TriangleRasterTarget target;
  std::vector<std::vector<Eigen::Vector3d>> in_camera;
  std::vector<int> first_id;  // meshes.size() + 1 entries
};

// Whether a mesh's box lies wholly behind the near plane or beside the image.
bool MeshBoxOutsideView(const PinholeCamera& camera, double near_m, const Eigen::Matrix3d& rotation,
                        const Eigen::Vector3d& translation, const Eigen::AlignedBox3d& bounds_in_world) {
  bool all_near = true, all_left = true, all_right = true, all_above = true, all_below = true;
  for (int k = 0; k < 8; ++k) {
    const Eigen::Vector3d c = rotation * bounds_in_world.corner(
                                             static_cast<Eigen::AlignedBox3d::CornerType>(k)) +
                              translation;
    all_near = all_near && c.z() < near_m;
    all_left = all_left && camera.fx * c.x() + camera.cx * c.z() < -0.5 * c.z();
    all_right = all_right && camera.fx * c.x() + camera.cx * c.z() > (camera.width - 0.5) * c.z();
    all_above = all_above && camera.fy * c.y() + camera.cy * c.z() < -0.5 * c.z();
    all_below = all_below && camera.fy * c.y() + camera.cy * c.z() > (camera.height - 0.5) * c.z();
  }
  return all_near || all_left || all_right || all_above || all_below;
}

// Rasterizes every mesh in view into `inv_depth` (shared: the quads' inverse
// depths are already there), both sides of each triangle.
void RasterizeMeshes(const std::vector<SceneMesh>& meshes,
                     const std::vector<std::vector<cv::Vec3f>>& vertex_light, const PinholeCamera& camera,
                     double near_m, const Rigid3d& camera_from_world, const cv::Mat& inv_depth,
                     MeshRaster* raster) {
  const cv::Size size(camera.width, camera.height);
  TriangleRasterTarget& target = raster->target;
  target.inv_depth = inv_depth;
  target.ids.create(size, CV_32SC1);
  target.ids.setTo(cv::Scalar(-1));
  target.barycentrics.create(size, CV_32FC2);
  TriangleRasterOptions options;
  options.near_m = near_m;
  options.cull_mode = CullMode::kNone;
  const Eigen::Matrix3d rotation = camera_from_world.rotation.toRotationMatrix();
  const Eigen::Vector3d& translation = camera_from_world.translation;
  std::vector<std::vector<Eigen::Vector3d>>& in_camera = raster->in_camera;
  std::vector<int>& first_id = raster->first_id;
  in_camera.assign(meshes.size(), {});
  first_id.assign(meshes.size() + 1, 0);
  for (size_t m = 0; m < meshes.size(); ++m) {
    const SceneMesh& mesh = meshes[m];
    SLAM_CHECK(vertex_light[m].size() == mesh.positions_in_world.size());
    first_id[m + 1] = first_id[m] + static_cast<int>(mesh.triangles.size());
    if (MeshBoxOutsideView(camera, near_m, rotation, translation, mesh.bounds_in_world)) continue;
    std::vector<Eigen::Vector3d>& points = in_camera[m];
    points.resize(mesh.positions_in_world.size());
    for (size_t v = 0; v < points.size(); ++v) {
      points[v] = rotation * mesh.positions_in_world[v].cast<double>() + translation;
    }
    for (size_t t = 0; t < mesh.triangles.size(); ++t) {
      const std::array<int, 3>& tri = mesh.triangles[t];
      RasterizeTriangle(camera, options, {points[tri[0]], points[tri[1]], points[tri[2]]},
                        first_id[m] + static_cast<int>(t), &target);
    }
  }
}

// The light at a mesh pixel: the vertex light interpolated, and with `sun`
// (a triangle it samples), the vertices' sun replaced by the sun at the pixel.
cv::Vec3f MeshPixelLight(const std::vector<cv::Vec3f>& light, const MeshSun* sun,
                         const std::array<int, 3>& tri, size_t triangle, float b0, float b1, float b2) {
  cv::Vec3f lit = light[tri[0]] * b0 + light[tri[1]] * b1 + light[tri[2]] * b2;
  if (sun != nullptr) {
    const int sampled = sun->triangle_samples[triangle];
    if (sampled >= 0) {
      // The vertices' sun out, the sun at this pixel in.
      const std::array<float, 3> b = {b0, b1, b2};
      cv::Vec3f unshadowed(0, 0, 0);
      for (int k = 0; k < 3; ++k) {
        const cv::Vec3f& s = sun->vertex_sun[static_cast<size_t>(tri[k])];
        unshadowed += s * b[k];
        if (sun->vertex_sun_visible[static_cast<size_t>(tri[k])]) lit -= s * b[k];
      }
      lit += unshadowed * sun->samples[static_cast<size_t>(sampled)].At(b1, b2);
    }
  }
  return lit;
}

// The albedo at a mesh pixel: the material's colour, times its mip-mapped
// texture sampled over the pixel's footprint.
cv::Vec3f MeshPixelAlbedo(const SceneMesh& mesh, const SceneMaterial& material, const std::array<int, 3>& tri,
                          float b1, float b2, const ProjectedTriangle& projected, int col, int row) {
  cv::Vec3f albedo = material.diffuse_bgr;
  if (material.texture) {
    const Eigen::Vector2f& t0 = mesh.texcoords[tri[0]];
    const Eigen::Vector2f e1 = (mesh.texcoords[tri[1]] - t0).cwiseProduct(material.texture_scale);
    const Eigen::Vector2f e2 = (mesh.texcoords[tri[2]] - t0).cwiseProduct(material.texture_scale);
    const Eigen::Vector2f uv =
        material.texture_offset + t0.cwiseProduct(material.texture_scale) + b1 * e1 + b2 * e2;
    const BarycentricDerivatives d = projected.Derivatives(col, row);
    const double footprint = FootprintTexels(
        d.d_dx(0) * e1.x() + d.d_dx(1) * e2.x(), d.d_dx(0) * e1.y() + d.d_dx(1) * e2.y(),
        d.d_dy(0) * e1.x() + d.d_dy(1) * e2.x(), d.d_dy(0) * e1.y() + d.d_dy(1) * e2.y(),
        material.texture->width(), material.texture->height());
    albedo = albedo.mul(material.texture->Sample(uv.x(), uv.y(), footprint));
  }
  return albedo;
}

// The cosine between the pixel's viewing ray and the triangle's normal.
float MeshPixelCosIncidence(const PinholeCamera& camera, const std::vector<Eigen::Vector3d>& points,
                            const std::array<int, 3>& tri, int col, int row) {
  const Eigen::Vector3d normal =
      (points[tri[1]] - points[tri[0]]).cross(points[tri[2]] - points[tri[0]]);
  const Eigen::Vector3d ray((col - camera.cx) / camera.fx, (row - camera.cy) / camera.fy, 1.0);
  const double denominator = normal.norm() * ray.norm();
  return denominator > 0.0 ? static_cast<float>(std::abs(normal.dot(ray)) / denominator) : 0.0f;
}

}  // namespace

void Renderer::RenderMeshes(const SessionRadiance& radiance, const Rigid3d& camera_from_world,
                            RenderedView* view) const {
  const std::vector<std::vector<cv::Vec3f>>& vertex_light = radiance.mesh_vertex_light;
  SLAM_CHECK(vertex_light.size() == scene_.meshes.size());
  SLAM_CHECK(radiance.mesh_sun.empty() || radiance.mesh_sun.size() == scene_.meshes.size());
  MeshRaster raster;
  RasterizeMeshes(scene_.meshes, vertex_light, camera_, near_m_, camera_from_world, view->depth_m, &raster);
  const std::vector<int>& first_id = raster.first_id;
  // Shading: the pixels a triangle won.
  const int num_quads = static_cast<int>(scene_.quads.size());
  int cached_id = -1;
  std::optional<ProjectedTriangle> projected;
  for (int row = 0; row < camera_.height; ++row) {
    const int* tri_row = raster.target.ids.ptr<int>(row);
    const cv::Vec2f* bary_row = raster.target.barycentrics.ptr<cv::Vec2f>(row);
    int* id_row = view->surface_id.ptr<int>(row);
    float* depth_row = view->depth_m.ptr<float>(row);
    cv::Vec3f* out = view->radiance.ptr<cv::Vec3f>(row);
    float* cos_out = view->cos_incidence.ptr<float>(row);
    for (int col = 0; col < camera_.width; ++col) {
      const int id = tri_row[col];
      if (id < 0) continue;
      const size_t m = static_cast<size_t>(
          std::upper_bound(first_id.begin(), first_id.end(), id) - first_id.begin() - 1);
      const SceneMesh& mesh = scene_.meshes[m];
      const size_t triangle = static_cast<size_t>(id - first_id[m]);
      const std::array<int, 3>& tri = mesh.triangles[triangle];
      const std::vector<Eigen::Vector3d>& points = raster.in_camera[m];
      if (id != cached_id) {
        projected.emplace(camera_, std::array<Eigen::Vector3d, 3>{points[tri[0]], points[tri[1]],
                                                                   points[tri[2]]});
        cached_id = id;
      }
      const float b1 = bary_row[col][0], b2 = bary_row[col][1], b0 = 1.0f - b1 - b2;
      const cv::Vec3f lit = MeshPixelLight(vertex_light[m], radiance.mesh_sun.empty() ? nullptr : &radiance.mesh_sun[m],
                                           tri, triangle, b0, b1, b2);
      const SceneMaterial& material = mesh.materials[static_cast<size_t>(mesh.triangle_material[triangle])];
      out[col] = MeshPixelAlbedo(mesh, material, tri, b1, b2, *projected, col, row).mul(lit);
      const double z = 1.0 / depth_row[col];
      depth_row[col] = static_cast<float>(z);
      id_row[col] = num_quads + static_cast<int>(m);
      cos_out[col] = MeshPixelCosIncidence(camera_, points, tri, col, row);
    }
  }
}

void Renderer::Render(const SessionRadiance& radiance, const Rigid3d& world_from_camera,
                      RenderedView* view) const {
  SLAM_CHECK_MSG(!(has_mirrors_ && radiance.window_view.enabled),
                 "Renderer::Render: mirrors are not supported with lighting.window_view_in_camera");
  RenderScene(radiance.quads, &radiance, &radiance.window_view, world_from_camera, view);
}

void Renderer::Render(const std::vector<cv::Mat>& radiance, const Rigid3d& world_from_camera,
                      RenderedView* view) const {
  SLAM_CHECK_MSG(scene_.meshes.empty(), "Renderer::Render: a scene with meshes needs its SessionRadiance");
  RenderScene(radiance, nullptr, nullptr, world_from_camera, view);
}

void Renderer::RenderScene(const std::vector<cv::Mat>& radiance, const SessionRadiance* meshes,
                           const WindowViewRadiance* window_view, const Rigid3d& world_from_camera,
                           RenderedView* view) const {
  SLAM_CHECK(radiance.size() == scene_.quads.size());
  const Rigid3d camera_from_world = world_from_camera.Inverse();
  const cv::Size size(camera_.width, camera_.height);
  // The depth pass writes inverse depth into depth_m (reused across frames);
  // the shading pass turns it into depth in place.
  view->depth_m.create(size, CV_32FC1);
  view->depth_m.setTo(cv::Scalar(0.0f));
  view->surface_id.create(size, CV_32SC1);
  view->surface_id.setTo(cv::Scalar(-1));
  std::vector<QuadSetup> setups(scene_.quads.size());
  for (size_t i = 0; i < scene_.quads.size(); ++i) {
    if (SetupQuad(scene_.quads[i], static_cast<int>(i), camera_from_world, false, &setups[i])) {
      RasterizeDepth(setups[i], &view->depth_m, &view->surface_id);
    }
  }
  const std::vector<Texture> textures = TexturesOf(radiance);
  view->radiance.create(size, CV_32FC3);
  view->cos_incidence.create(size, CV_32FC1);
  if (meshes != nullptr && !scene_.meshes.empty()) {
    RenderMeshes(*meshes, camera_from_world, view);
  }
  const int num_quads = static_cast<int>(scene_.quads.size());
  const double inv_fx = 1.0 / camera_.fx;
  const Eigen::Matrix3d world_from_camera_rotation = world_from_camera.rotation.toRotationMatrix();
  const WindowViewRadiance* panes = window_view != nullptr && window_view->enabled ? window_view : nullptr;
  for (int row = 0; row < size.height; ++row) {
    const int* id_row = view->surface_id.ptr<int>(row);
    float* depth_row = view->depth_m.ptr<float>(row);
    float* out = view->radiance.ptr<float>(row);
    float* cos_out = view->cos_incidence.ptr<float>(row);
    const double dy = (row - camera_.cy) / camera_.fy;
    const double ray_base = dy * dy + 1.0;
    for (int col = 0; col < size.width; ++col, out += 3) {
      const int id = id_row[col];
      if (id < 0) {
        out[0] = out[1] = out[2] = 0.0f;
        depth_row[col] = 0.0f;
        cos_out[col] = 0.0f;
        continue;
      }
      if (id >= num_quads) continue;  // a mesh, shaded already
      const QuadSetup& s = setups[id];
      const double z = 1.0 / depth_row[col];
      Sample(s, textures[id], col, row, z, out);
      depth_row[col] = static_cast<float>(z);
      const double dx = (col - camera_.cx) * inv_fx;
      if (panes != nullptr && scene_.quads[id].emission == Emission::kSky) {
        // The pane mask times what this pixel's ray sees outside.
        const cv::Vec3f seen = panes->Seen(id, world_from_camera_rotation * Eigen::Vector3d(dx, dy, 1.0));
        for (int c = 0; c < 3; ++c) out[c] *= seen[c];
      }
      const double n_dot_d = s.cos_a * col + s.cos_b * row + s.cos_c;
      cos_out[col] = static_cast<float>(std::abs(n_dot_d) / std::sqrt(dx * dx + ray_base));
    }
  }
  if (!has_mirrors_) return;
  std::vector<bool> seen(scene_.quads.size(), false);
  for (int row = 0; row < size.height; ++row) {
    const int* id_row = view->surface_id.ptr<int>(row);
    for (int col = 0; col < size.width; ++col) {
      if (id_row[col] >= 0 && id_row[col] < num_quads) seen[id_row[col]] = true;
    }
  }
  for (size_t i = 0; i < scene_.quads.size(); ++i) {
    if (seen[i] && scene_.quads[i].mirror_reflectance > 0.0) {
      AddReflection(static_cast<int>(i), radiance, camera_from_world, view);
    }
  }
}

}  // namespace duskmap
