// Z-buffer rasterization of camera-frame triangles (the furniture meshes)
// into the renderer's kind of buffers: inverse depth, ids, and the
// perspective-correct barycentrics a shading pass turns into texture
// coordinates. Single-threaded and deterministic.
//
// Conventions, matching renderer.cc and PinholeCamera:
//  - Pixel (col, row) samples the ray through its centre, at integer image
//    coordinates (x, y) = (col, row): d = ((x - cx) / fx, (y - cy) / fy, 1).
//  - Front faces are counter-clockwise seen from the front (OBJ, and
//    TriangleMesh): the normal (v1 - v0) x (v2 - v0) points towards the
//    camera. In the image (x right, y down) a front face runs
//    counter-clockwise as it appears on screen. The quad renderer culls the
//    same way (n = u x v towards the camera).
//  - Coverage is decided by homogeneous edge functions (Olano and Greer,
//    "Triangle scan conversion using 2D homogeneous coordinates", 1997):
//    e_i(x, y) = (v_j x v_k) . d, for (i, j, k) cyclic, is affine in (x, y),
//    and the ray's point on the triangle's plane has barycentrics
//    b_i = e_i / (e_0 + e_1 + e_2) and inverse depth
//    1/z = (e_0 + e_1 + e_2) / (v_0 . (v_1 x v_2)). A pixel is covered when
//    its point lies in the triangle, in front of the camera and no nearer
//    than the near plane; the near plane is one more half-plane in the
//    image (1/z <= 1/near is affine in (x, y)), so the part of a triangle
//    beyond it is drawn exactly as clipping it into 0, 1 or 2 triangles
//    would draw it, with the barycentrics of the original triangle and no
//    new vertices. Vertices behind the camera are handled alike.
//  - Fill rule: a pixel centre exactly on an edge belongs to the triangle
//    whose inside lies to its right (+x), or, for a horizontal edge, below
//    it (+y): the top-left rule. Each edge function is evaluated the same
//    way by the two triangles that share the edge (their vertices ordered
//    canonically), so one is the exact negation of the other: triangles
//    with bitwise-equal shared vertices cover each pixel exactly once.
//  - Depth test on inverse depth as stored (float): a fragment is written
//    when it is strictly nearer than what the pixel holds; ties keep the
//    first.
#pragma once

#include <array>
#include <cmath>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "slam/core/camera.h"

namespace duskmap {

enum class CullMode {
  kNone,   // draw both sides
  kBack,   // draw front faces only (the default)
  kFront,  // draw back faces only (e.g. a mirrored image, whose winding is reversed)
};

struct TriangleRasterOptions {
  double near_m = 0.05;  // near plane z = near_m (metres, > 0); nearer parts are not drawn
  CullMode cull_mode = CullMode::kBack;

  void Check() const;  // throws ConfigError naming the field
};

// What the triangles are drawn into, at the camera's size.
struct TriangleRasterTarget {
  cv::Mat inv_depth;     // CV_32FC1, 1/z in 1/m; 0 = empty, larger = nearer
  cv::Mat ids;           // CV_32SC1, the drawn triangle's id; -1 = empty
  // CV_32FC2 (b1, b2): the perspective-correct barycentrics of the pixel's
  // point in the ORIGINAL triangle (vertices 1 and 2; b0 = 1 - b1 - b2), so
  // point = b0 v0 + b1 v1 + b2 v2 and likewise for texture coordinates.
  // Undefined where ids is -1.
  cv::Mat barycentrics;

  // (Re)allocates the buffers at the camera's size and empties them.
  void Reset(const PinholeCamera& camera);
};

// Screen-space derivatives of the barycentrics (b1, b2) at a pixel, per
// pixel along image x (columns) and y (rows). Texture coordinates
// uv = uv0 + b1 (uv1 - uv0) + b2 (uv2 - uv0) have
// duv/dx = d_dx(0) (uv1 - uv0) + d_dx(1) (uv2 - uv0), and likewise along y;
// FootprintTexels (mip_texture.h) turns them into a level of detail.
struct BarycentricDerivatives {
  Eigen::Vector2d d_dx = Eigen::Vector2d::Zero();
  Eigen::Vector2d d_dy = Eigen::Vector2d::Zero();
};

// A camera-frame triangle's edge functions in the image: what the
// rasterizer decides coverage with, and what a shading pass evaluates the
// barycentrics' derivatives with (analytic: with S = e_0 + e_1 + e_2 and
// a_i = de_i/dx, db_i/dx = (a_i - b_i sum_k a_k) / S). Building one costs a
// few cross products, so a caller may build it per pixel from the
// triangle's camera-frame vertices, or once per triangle.
class ProjectedTriangle {
 public:
  ProjectedTriangle(const PinholeCamera& camera, const std::array<Eigen::Vector3d, 3>& vertices_in_camera);

  // v0 . (v1 x v2): negative for a front face, positive for a back face,
  // zero (or NaN for non-finite vertices) when the triangle is degenerate
  // or seen edge-on; such a triangle covers nothing.
  double signed_volume() const { return volume_; }
  bool drawable() const { return volume_ != 0.0 && std::isfinite(volume_); }
  bool front_facing() const { return volume_ < 0.0; }

  // At image point (x, y) (pixel centres at integers), the point of the
  // triangle's plane on the ray through it: barycentrics (b0, b1, b2) and
  // inverse depth 1/z (negative where the plane lies behind the camera).
  // Undefined when !drawable().
  Eigen::Vector3d Barycentrics(double x, double y) const;
  double InverseDepth(double x, double y) const;
  BarycentricDerivatives Derivatives(double x, double y) const;

 private:
  friend int RasterizeTriangle(const PinholeCamera&, const TriangleRasterOptions&,
                               const std::array<Eigen::Vector3d, 3>&, int, TriangleRasterTarget*);
  // e = sign * (a x + (b y + c)); (a, b, c) from the edge's two vertices in
  // a canonical order, so that a neighbour evaluates the same expression.
  struct Edge {
    double a = 0.0, b = 0.0, c = 0.0;
    double sign = 1.0;
    double At(double x, double y) const { return sign * (a * x + (b * y + c)); }
  };
  Edge edges_[3];
  double volume_ = 0.0;
};

// Draws the triangle with vertices in the camera frame (metres) into
// `target` (Reset to this camera's size) with id `id`, and returns the
// number of pixels written (that passed the depth test). Throws ConfigError
// for invalid options; non-finite or degenerate triangles draw nothing.
int RasterizeTriangle(const PinholeCamera& camera, const TriangleRasterOptions& options,
                      const std::array<Eigen::Vector3d, 3>& vertices_in_camera, int id,
                      TriangleRasterTarget* target);

}  // namespace duskmap
