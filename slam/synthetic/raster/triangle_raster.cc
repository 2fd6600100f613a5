#include "slam/synthetic/raster/triangle_raster.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Geometry>

#include "slam/core/check.h"

namespace duskmap {

void TriangleRasterOptions::Check() const {
  SLAM_THROW_IF_NOT(ConfigError, std::isfinite(near_m) && near_m > 0.0)
      << "triangle_raster.near_m must be a finite value > 0, got " << near_m;
  SLAM_THROW_IF_NOT(ConfigError, cull_mode == CullMode::kNone || cull_mode == CullMode::kBack ||
                                     cull_mode == CullMode::kFront)
      << "triangle_raster.cull_mode is not a CullMode, got " << static_cast<int>(cull_mode);
}

void TriangleRasterTarget::Reset(const PinholeCamera& camera) {
  const cv::Size size(camera.width, camera.height);
  inv_depth.create(size, CV_32FC1);
  inv_depth.setTo(cv::Scalar(0.0f));
  ids.create(size, CV_32SC1);
  ids.setTo(cv::Scalar(-1));
  barycentrics.create(size, CV_32FC2);
  barycentrics.setTo(cv::Scalar::all(0.0));
}

namespace {

bool LexicographicallyLess(const Eigen::Vector3d& p, const Eigen::Vector3d& q) {
  if (p.x() != q.x()) return p.x() < q.x();
  if (p.y() != q.y()) return p.y() < q.y();
  return p.z() < q.z();
}

// (p x q) computed in the canonical order of p and q, and the sign that
// turns it into p x q: the same bits for an edge and its reverse.
Eigen::Vector3d CanonicalCross(const Eigen::Vector3d& p, const Eigen::Vector3d& q, double* sign) {
  const bool in_order = LexicographicallyLess(p, q);
  *sign = in_order ? 1.0 : -1.0;
  return in_order ? p.cross(q) : q.cross(p);
}

// v0 . (v1 x v2), the way ProjectedTriangle::signed_volume computes it.
double SignedVolume(const std::array<Eigen::Vector3d, 3>& v) {
  double sign;
  const Eigen::Vector3d n = CanonicalCross(v[1], v[2], &sign);
  return sign * v[0].dot(n);
}

}  // namespace

ProjectedTriangle::ProjectedTriangle(const PinholeCamera& camera,
                                     const std::array<Eigen::Vector3d, 3>& v) {
  const double inv_fx = 1.0 / camera.fx, inv_fy = 1.0 / camera.fy;
  for (int i = 0; i < 3; ++i) {
    Edge& e = edges_[i];
    // e_i = (v_j x v_k) . d, and d = ((x - cx) / fx, (y - cy) / fy, 1), so
    // e_i = sign * (a x + b y + c).
    const Eigen::Vector3d n = CanonicalCross(v[(i + 1) % 3], v[(i + 2) % 3], &e.sign);
    e.a = n.x() * inv_fx;
    e.b = n.y() * inv_fy;
    e.c = n.z() - e.a * camera.cx - e.b * camera.cy;
  }
  volume_ = SignedVolume(v);
}

Eigen::Vector3d ProjectedTriangle::Barycentrics(double x, double y) const {
  const Eigen::Vector3d e(edges_[0].At(x, y), edges_[1].At(x, y), edges_[2].At(x, y));
  return e / e.sum();
}

double ProjectedTriangle::InverseDepth(double x, double y) const {
  return (edges_[0].At(x, y) + edges_[1].At(x, y) + edges_[2].At(x, y)) / volume_;
}

BarycentricDerivatives ProjectedTriangle::Derivatives(double x, double y) const {
  const Eigen::Vector3d e(edges_[0].At(x, y), edges_[1].At(x, y), edges_[2].At(x, y));
  const double s = e.sum();
  const Eigen::Vector3d b = e / s;
  Eigen::Vector3d de_dx, de_dy;
  for (int i = 0; i < 3; ++i) {
    de_dx[i] = edges_[i].sign * edges_[i].a;
    de_dy[i] = edges_[i].sign * edges_[i].b;
  }
  BarycentricDerivatives d;
  for (int i = 1; i <= 2; ++i) {
    d.d_dx[i - 1] = (de_dx[i] - b[i] * de_dx.sum()) / s;
    d.d_dy[i - 1] = (de_dy[i] - b[i] * de_dy.sum()) / s;
  }
  return d;
}

namespace {

// Widening of the pixel bounds, relative to the coordinates (and at least
// this in pixels).
constexpr double kBoundsSlackPx = 1e-6;

// Pixel rectangle (inclusive) that holds the image of the triangle's part
// at z >= near_m, or an empty one (col_begin > col_end).
struct PixelBounds {
  int col_begin = 0, col_end = -1, row_begin = 0, row_end = -1;
};

PixelBounds NearClippedBounds(const PinholeCamera& camera, const std::array<Eigen::Vector3d, 3>& v,
                              double near_m) {
  double x_min = std::numeric_limits<double>::infinity(), x_max = -x_min;
  double y_min = x_min, y_max = -x_min;
  auto add = [&](const Eigen::Vector3d& p) {
    const double x = camera.fx * p.x() / p.z() + camera.cx, y = camera.fy * p.y() / p.z() + camera.cy;
    x_min = std::min(x_min, x);
    x_max = std::max(x_max, x);
    y_min = std::min(y_min, y);
    y_max = std::max(y_max, y);
  };
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector3d& a = v[i];
    const Eigen::Vector3d& b = v[(i + 1) % 3];
    const bool a_in = a.z() >= near_m, b_in = b.z() >= near_m;
    if (a_in) add(a);
    if (a_in != b_in) {
      const Eigen::Vector3d& in = a_in ? a : b;
      const Eigen::Vector3d& out = a_in ? b : a;
      Eigen::Vector3d p = in + (out - in) * ((near_m - in.z()) / (out.z() - in.z()));
      p.z() = near_m;
      add(p);
    }
  }
  PixelBounds bounds;
  if (!(x_min <= x_max && y_min <= y_max)) return bounds;  // nothing in front (or NaN)
  // Pixel centres are at integers. The slack (far beyond the rounding of the
  // projections and of the edge functions) keeps the bounds conservative.
  auto slack = [](double t) { return kBoundsSlackPx * (1.0 + std::abs(t)); };
  bounds.col_begin = static_cast<int>(std::max(0.0, std::ceil(x_min - slack(x_min))));
  bounds.col_end = static_cast<int>(std::min(camera.width - 1.0, std::floor(x_max + slack(x_max))));
  bounds.row_begin = static_cast<int>(std::max(0.0, std::ceil(y_min - slack(y_min))));
  bounds.row_end = static_cast<int>(std::min(camera.height - 1.0, std::floor(y_max + slack(y_max))));
  return bounds;
}

// Restricts [lo, hi] to the x where slope * x + offset >= 0, widened by
// more than the rounding of the exact per-pixel test (that decides), given
// |x| <= x_scale. Returns false when no x of the row can pass.
bool RestrictSpan(double slope, double offset, double x_scale, double* lo, double* hi) {
  if (slope == 0.0) return offset >= 0.0;
  const double bound = -offset / slope;
  const double slack = 1.0 + 1e-9 * (std::abs(slope) * x_scale + std::abs(offset)) / std::abs(slope);
  if (slope > 0.0) {
    *lo = std::max(*lo, bound - slack);
  } else {
    *hi = std::min(*hi, bound + slack);
  }
  return true;
}

// Spans narrower than this are tested pixel by pixel without solving for
// the edges' crossings.
constexpr int kMinSpanForCrossings = 8;

// A drawable triangle's edge functions as RasterizeTriangle walks them:
// e_i = sign[i] * (a[i] x + (b[i] y + c[i])), normalised by the facing so
// that a pixel is inside where all are >= 0 (then their sum S > 0 and
// 1/z = S / |volume| > 0).
struct EdgeWalk {
  double a[3], b[3], c[3];
  double sign[3], slope[3];
  bool tie_inside[3];
  double inv_slope = 0.0;  // d(1/z)/dx
  double inv_volume = 0.0;
  double inv_near = 0.0;
};

// Narrows [lo, hi] to the columns of a row where every edge function (and
// inv_near - 1/z) can be >= 0; false when an edge rules the row out.
bool RowSpan(const EdgeWalk& w, const double row_term[3], double x_scale, double* lo, double* hi) {
  bool possible = true;
  double inv_offset = 0.0;
  for (int i = 0; i < 3 && possible; ++i) {
    possible = RestrictSpan(w.slope[i], w.sign[i] * row_term[i], x_scale, lo, hi);
    inv_offset += w.sign[i] * row_term[i] * w.inv_volume;
  }
  // 1/z <= 1/near_m, i.e. inv_near - 1/z >= 0.
  if (possible && w.inv_slope != 0.0) RestrictSpan(-w.inv_slope, w.inv_near - inv_offset, x_scale, lo, hi);
  return possible;
}

// Draws columns [col_begin, col_end] of one row: the pixels inside the
// triangle (top-left rule on ties), nearer than the near plane's 1/z and
// than what the target holds. Returns the pixels written.
int RasterizeRow(const EdgeWalk& w, int row, const double row_term[3], int col_begin, int col_end, int id,
                 TriangleRasterTarget* target) {
  float* depth_row = target->inv_depth.ptr<float>(row);
  int* id_row = target->ids.ptr<int>(row);
  cv::Vec2f* bary_row = target->barycentrics.ptr<cv::Vec2f>(row);
  int written = 0;
  for (int col = col_begin; col <= col_end; ++col) {
    const double x = col;
    // The same expression as ProjectedTriangle::Edge::At, times +-1.
    const double e0 = w.sign[0] * (w.a[0] * x + row_term[0]);
    const double e1 = w.sign[1] * (w.a[1] * x + row_term[1]);
    const double e2 = w.sign[2] * (w.a[2] * x + row_term[2]);
    if (!(e0 > 0.0 || (e0 == 0.0 && w.tie_inside[0]))) continue;
    if (!(e1 > 0.0 || (e1 == 0.0 && w.tie_inside[1]))) continue;
    if (!(e2 > 0.0 || (e2 == 0.0 && w.tie_inside[2]))) continue;
    const double s = e0 + e1 + e2;
    if (!(s > 0.0)) continue;
    const double inv = s * w.inv_volume;
    if (inv > w.inv_near) continue;
    const float inv_f = static_cast<float>(inv);
    if (!(inv_f > depth_row[col])) continue;
    depth_row[col] = inv_f;
    id_row[col] = id;
    const double inv_s = 1.0 / s;
    bary_row[col] = cv::Vec2f(static_cast<float>(e1 * inv_s), static_cast<float>(e2 * inv_s));
    ++written;
  }
  return written;
}

void CheckRasterTarget(const PinholeCamera& camera, const TriangleRasterTarget* target) {
  SLAM_CHECK(camera.IsValid());
  SLAM_CHECK(target != nullptr && target->inv_depth.type() == CV_32FC1 && target->ids.type() == CV_32SC1 &&
             target->barycentrics.type() == CV_32FC2);
  SLAM_CHECK(target->inv_depth.cols == camera.width && target->inv_depth.rows == camera.height &&
             target->ids.size() == target->inv_depth.size() &&
             target->barycentrics.size() == target->inv_depth.size());
}

}  // namespace

int RasterizeTriangle(const PinholeCamera& camera, const TriangleRasterOptions& options,
                      const std::array<Eigen::Vector3d, 3>& vertices_in_camera, int id,
                      TriangleRasterTarget* target) {
  options.Check();
  CheckRasterTarget(camera, target);
  // Culled, degenerate or non-finite: nothing to set up.
  const double volume = SignedVolume(vertices_in_camera);
  if (!(volume != 0.0 && std::isfinite(volume))) return 0;
  if (options.cull_mode == CullMode::kBack && volume > 0.0) return 0;
  if (options.cull_mode == CullMode::kFront && volume < 0.0) return 0;
  const ProjectedTriangle triangle(camera, vertices_in_camera);
  const PixelBounds bounds = NearClippedBounds(camera, vertices_in_camera, options.near_m);
  if (bounds.col_begin > bounds.col_end || bounds.row_begin > bounds.row_end) return 0;

  // Edge values normalised by the facing: inside where all are >= 0
  // (then their sum S > 0 and 1/z = S / |volume| > 0).
  const double facing = triangle.front_facing() ? -1.0 : 1.0;
  const ProjectedTriangle::Edge* edges = triangle.edges_;
  EdgeWalk w;
  w.inv_volume = 1.0 / std::abs(triangle.signed_volume());
  for (int i = 0; i < 3; ++i) {
    w.a[i] = edges[i].a;
    w.b[i] = edges[i].b;
    w.c[i] = edges[i].c;
    w.sign[i] = facing * edges[i].sign;
    w.slope[i] = w.sign[i] * edges[i].a;
    const double slope_y = w.sign[i] * edges[i].b;
    w.tie_inside[i] = w.slope[i] > 0.0 || (w.slope[i] == 0.0 && slope_y > 0.0);  // top-left rule
    w.inv_slope += w.slope[i] * w.inv_volume;
  }
  w.inv_near = 1.0 / options.near_m;
  const bool solve_spans = bounds.col_end - bounds.col_begin >= kMinSpanForCrossings;
  const double x_scale = camera.width;
  int written = 0;
  for (int row = bounds.row_begin; row <= bounds.row_end; ++row) {
    const double y = row;
    double row_term[3];
    for (int i = 0; i < 3; ++i) row_term[i] = w.b[i] * y + w.c[i];
    double lo = bounds.col_begin, hi = bounds.col_end;
    if (solve_spans) {
      const bool possible = RowSpan(w, row_term, x_scale, &lo, &hi);
      if (!possible || lo > hi) continue;
    }
    const int col_begin = std::max(bounds.col_begin, static_cast<int>(std::floor(lo)));
    const int col_end = std::min(bounds.col_end, static_cast<int>(std::ceil(hi)));
    written += RasterizeRow(w, row, row_term, col_begin, col_end, id, target);
  }
  return written;
}

}  // namespace duskmap
