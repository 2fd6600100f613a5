#include "slam/synthetic/raster/triangle_raster.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "slam/core/check.h"
#include "slam/core/rigid3.h"
#include "slam/synthetic/raster/triangle_bvh.h"

namespace duskmap {
namespace {

using Triangle = std::array<Eigen::Vector3d, 3>;

PinholeCamera SmallCamera() {
  PinholeCamera c;
  c.width = 160;
  c.height = 120;
  c.fx = 110.0;
  c.fy = 105.0;
  c.cx = 79.5;
  c.cy = 59.5;
  return c;
}

TriangleRasterOptions Options(CullMode cull_mode, double near_m = 0.05) {
  TriangleRasterOptions options;
  options.cull_mode = cull_mode;
  options.near_m = near_m;
  return options;
}

Eigen::Vector3d Ray(const PinholeCamera& c, double x, double y) {
  return Eigen::Vector3d((x - c.cx) / c.fx, (y - c.cy) / c.fy, 1.0);
}

// The ray through pixel (x, y) meets the triangle's plane at depth z (the
// ray's z is 1): z = n . v0 / n . d.
double PlaneDepth(const PinholeCamera& c, const Triangle& t, double x, double y) {
  const Eigen::Vector3d n = (t[1] - t[0]).cross(t[2] - t[0]);
  return n.dot(t[0]) / n.dot(Ray(c, x, y));
}

// Signed distances (pixels) of image point p to the projected triangle's
// edges, positive inside, for a triangle wholly in front of the camera.
std::array<double, 3> EdgeDistances(const PinholeCamera& c, const Triangle& t, const Eigen::Vector2d& p) {
  Eigen::Vector2d q[3] = {Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero()};
  for (int i = 0; i < 3; ++i) c.Project(t[i], &q[i]);
  const double area = (q[1] - q[0]).x() * (q[2] - q[0]).y() - (q[1] - q[0]).y() * (q[2] - q[0]).x();
  std::array<double, 3> d;
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector2d& a = q[(i + 1) % 3];
    const Eigen::Vector2d& b = q[(i + 2) % 3];
    const double cross = (b - a).x() * (p - a).y() - (b - a).y() * (p - a).x();
    d[i] = (area > 0 ? cross : -cross) / (b - a).norm();
  }
  return d;
}

Eigen::Vector3d Reconstruct(const Triangle& t, const cv::Vec2f& b) {
  return (1.0 - b[0] - b[1]) * t[0] + b[0] * t[1] + b[1] * t[2];
}

// A triangle facing the camera is counter-clockwise on screen; this one is
// front-facing by the convention's definition.
TEST(TriangleRaster, FrontFacesAreCounterClockwiseSeenFromTheFront) {
  const Triangle t = {Eigen::Vector3d(0, 0, 2), Eigen::Vector3d(1, 0, 2), Eigen::Vector3d(0, -1, 2)};
  EXPECT_LT((t[1] - t[0]).cross(t[2] - t[0]).dot(t[0]), 0.0);
  EXPECT_TRUE(ProjectedTriangle(SmallCamera(), t).front_facing());
}

TEST(TriangleRaster, CoversThePixelCentresOfTheProjectedTriangleAtThePlaneDepth) {
  const PinholeCamera camera = SmallCamera();
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> xy(-1.5, 1.5), z(1.0, 4.0);
  int checked = 0;
  for (int trial = 0; trial < 40; ++trial) {
    Triangle t;
    for (Eigen::Vector3d& v : t) v = Eigen::Vector3d(xy(rng), xy(rng), z(rng));
    TriangleRasterTarget target;
    target.Reset(camera);
    const int written = RasterizeTriangle(camera, Options(CullMode::kNone), t, 7, &target);
    int covered = 0;
    for (int row = 0; row < camera.height; ++row) {
      for (int col = 0; col < camera.width; ++col) {
        const std::array<double, 3> d = EdgeDistances(camera, t, Eigen::Vector2d(col, row));
        const double margin = std::min({std::abs(d[0]), std::abs(d[1]), std::abs(d[2])});
        const bool inside = d[0] > 0 && d[1] > 0 && d[2] > 0;
        const int id = target.ids.at<int>(row, col);
        covered += id == 7;
        if (margin < 1e-6) continue;  // on an edge: the fill rule decides
        ASSERT_EQ(id == 7, inside) << "pixel " << col << "," << row << " trial " << trial;
        if (!inside) continue;
        ++checked;
        const double depth = 1.0 / target.inv_depth.at<float>(row, col);
        EXPECT_NEAR(depth, PlaneDepth(camera, t, col, row), 1e-4 * depth);
        // The barycentrics give back the point on the pixel's ray.
        const Eigen::Vector3d p = Reconstruct(t, target.barycentrics.at<cv::Vec2f>(row, col));
        Eigen::Vector2d pixel;
        ASSERT_TRUE(camera.Project(p, &pixel));
        EXPECT_NEAR(pixel.x(), col, 1e-3);
        EXPECT_NEAR(pixel.y(), row, 1e-3);
      }
    }
    EXPECT_EQ(written, covered);
  }
  EXPECT_GT(checked, 5000);
}

// Every triangle into its own target; returns how many of them cover each pixel.
cv::Mat CoverageCounts(const PinholeCamera& camera, const TriangleRasterOptions& options,
                       const std::vector<Triangle>& triangles) {
  cv::Mat counts(camera.height, camera.width, CV_32SC1, cv::Scalar(0));
  TriangleRasterTarget target;
  for (size_t i = 0; i < triangles.size(); ++i) {
    target.Reset(camera);
    RasterizeTriangle(camera, options, triangles[i], static_cast<int>(i), &target);
    for (int row = 0; row < camera.height; ++row) {
      for (int col = 0; col < camera.width; ++col) counts.at<int>(row, col) += target.ids.at<int>(row, col) >= 0;
    }
  }
  return counts;
}

TEST(TriangleRaster, TwoTrianglesOfAQuadCoverEachPixelExactlyOnce) {
  const PinholeCamera camera = SmallCamera();
  // Corners on pixel centres (depth 2): the diagonal and the borders pass
  // through pixel centres up to rounding.
  auto point = [&](double x, double y) { return camera.Unproject(x, y, 2.0); };
  const Eigen::Vector3d a = point(10, 10), b = point(150, 10), c = point(150, 100), d = point(10, 100);
  // Counter-clockwise on screen (y down): a, d, c, then a, c, b.
  const std::vector<Triangle> quad = {{a, d, c}, {a, c, b}};
  const cv::Mat counts = CoverageCounts(camera, Options(CullMode::kBack), quad);
  for (int row = 0; row < camera.height; ++row) {
    for (int col = 0; col < camera.width; ++col) {
      const bool interior = col > 10 && col < 150 && row > 10 && row < 100;
      const bool outside = col < 10 || col > 150 || row < 10 || row > 100;
      const int count = counts.at<int>(row, col);
      if (interior) {
        ASSERT_EQ(count, 1) << col << "," << row;
      } else if (outside) {
        ASSERT_EQ(count, 0) << col << "," << row;
      } else {
        ASSERT_LE(count, 1) << col << "," << row;  // on the border: rounding decides
      }
    }
  }
}

// With exactly representable coordinates the edge functions are exact, and
// centres on an edge are decided by the top-left rule: the left and top
// borders are in, the right and bottom ones out, the diagonal once.
TEST(TriangleRaster, CentresExactlyOnAnEdgeFollowTheTopLeftRule) {
  PinholeCamera camera;
  camera.width = camera.height = 64;
  camera.fx = camera.fy = 64.0;
  camera.cx = camera.cy = 32.0;
  auto point = [&](double x, double y) { return camera.Unproject(x, y, 1.0); };
  const Eigen::Vector3d a = point(8, 8), b = point(24, 8), c = point(24, 24), d = point(8, 24);
  for (const std::vector<Triangle>& quad : {std::vector<Triangle>{{a, d, c}, {a, c, b}},
                                            std::vector<Triangle>{{a, d, b}, {b, d, c}}}) {
    const cv::Mat counts = CoverageCounts(camera, Options(CullMode::kBack), quad);
    for (int row = 0; row < camera.height; ++row) {
      for (int col = 0; col < camera.width; ++col) {
        const bool in = col >= 8 && col < 24 && row >= 8 && row < 24;
        ASSERT_EQ(counts.at<int>(row, col), in ? 1 : 0) << col << "," << row;
      }
    }
  }
}

TEST(TriangleRaster, AMeshOverTheWholeViewCoversEachPixelExactlyOnce) {
  const PinholeCamera camera = SmallCamera();
  // A bumpy height field (not planar) in front of the camera, beyond the
  // image on every side, with jittered vertices and both diagonals.
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> jitter(-0.04, 0.04), bump(-0.3, 0.3);
  const int n = 12;
  std::vector<Eigen::Vector3d> grid;
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      const double z = 2.0 + bump(rng);
      const double x = (-1.0 + 2.0 * i / n + jitter(rng)) * 1.4 * z;
      const double y = (-1.0 + 2.0 * j / n + jitter(rng)) * 1.4 * z;
      grid.emplace_back(x, y, z);
    }
  }
  std::vector<Triangle> triangles;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const Eigen::Vector3d& p00 = grid[j * (n + 1) + i];
      const Eigen::Vector3d& p10 = grid[j * (n + 1) + i + 1];
      const Eigen::Vector3d& p01 = grid[(j + 1) * (n + 1) + i];
      const Eigen::Vector3d& p11 = grid[(j + 1) * (n + 1) + i + 1];
      if ((i + j) % 2 == 0) {
        triangles.push_back({p00, p01, p11});
        triangles.push_back({p00, p11, p10});
      } else {
        triangles.push_back({p00, p01, p10});
        triangles.push_back({p10, p01, p11});
      }
    }
  }
  for (const Triangle& t : triangles) ASSERT_TRUE(ProjectedTriangle(camera, t).front_facing());
  const cv::Mat counts = CoverageCounts(camera, Options(CullMode::kBack), triangles);
  double min_count, max_count;
  cv::minMaxLoc(counts, &min_count, &max_count);
  EXPECT_EQ(min_count, 1);
  EXPECT_EQ(max_count, 1);
}

// A bumpy floor that runs from behind the camera to 8 m ahead, cut by a
// near plane at 1 m: each pixel is drawn at most once, and exactly where a
// ray through it meets the floor beyond the near plane (ray casting with
// the BVH as the reference).
TEST(TriangleRaster, AMeshCutByTheNearPlaneAgreesWithRayCasting) {
  const PinholeCamera camera = SmallCamera();
  const double near_m = 1.0;
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> bump(-0.04, 0.04);
  const int nx = 16, nz = 12;
  std::vector<Eigen::Vector3d> grid;
  for (int j = 0; j <= nz; ++j) {
    for (int i = 0; i <= nx; ++i) grid.emplace_back(-8.0 + 16.0 * i / nx, 0.5 + bump(rng), -1.0 + 9.0 * j / nz);
  }
  std::vector<Triangle> triangles;
  std::vector<WorldTriangle> for_bvh;
  for (int j = 0; j < nz; ++j) {
    for (int i = 0; i < nx; ++i) {
      const int k = j * (nx + 1) + i;
      for (const Triangle& t : {Triangle{grid[k], grid[k + 1], grid[k + nx + 2]},
                                Triangle{grid[k], grid[k + nx + 2], grid[k + nx + 1]}}) {
        triangles.push_back(t);
        for_bvh.push_back({t[0].cast<float>(), t[1].cast<float>(), t[2].cast<float>()});
      }
    }
  }
  TriangleBvhOptions bvh_options;
  bvh_options.min_distance_m = 0.0;
  const TriangleBvh bvh(for_bvh, bvh_options);
  const cv::Mat counts = CoverageCounts(camera, Options(CullMode::kNone, near_m), triangles);
  int drawn = 0, clipped = 0;
  for (int row = 0; row < camera.height; ++row) {
    for (int col = 0; col < camera.width; ++col) {
      const int count = counts.at<int>(row, col);
      ASSERT_LE(count, 1) << col << "," << row;
      const Eigen::Vector3d d = Ray(camera, col, row);
      const std::optional<TriangleHit> hit = bvh.Intersect(Eigen::Vector3d::Zero(), d.normalized(), 100.0);
      if (!hit) continue;  // beyond the floor's far edge, or above the horizon
      const double z = hit->distance_m / d.norm();
      const double margin = std::min({hit->b1, hit->b2, 1.0 - hit->b1 - hit->b2});
      if (margin < 1e-6) continue;  // on an edge: the fill rule decides
      if (z > near_m * (1 + 1e-6)) {
        ASSERT_EQ(count, 1) << col << "," << row;
        ++drawn;
      } else if (z < near_m * (1 - 1e-6)) {
        ASSERT_EQ(count, 0) << col << "," << row;
        ++clipped;
      }
    }
  }
  EXPECT_GT(drawn, 3000);
  EXPECT_GT(clipped, 300);
}

TEST(TriangleRaster, ClipsAtTheNearPlaneKeepingTheOriginalTrianglesBarycentrics) {
  const PinholeCamera camera = SmallCamera();
  const double near_m = 0.5;
  // One vertex nearer than the near plane, and one behind the camera.
  const std::vector<Triangle> cases = {
      {Eigen::Vector3d(-1.0, -0.8, 2.0), Eigen::Vector3d(0.0, 0.6, 0.2), Eigen::Vector3d(1.2, -0.5, 3.0)},
      {Eigen::Vector3d(-1.0, -0.8, 2.0), Eigen::Vector3d(0.1, 0.9, -1.0), Eigen::Vector3d(1.2, -0.5, 3.0)},
      {Eigen::Vector3d(-0.3, -0.2, 0.3), Eigen::Vector3d(0.1, 0.9, -1.0), Eigen::Vector3d(1.2, -0.5, 3.0)},
  };
  for (size_t k = 0; k < cases.size(); ++k) {
    const Triangle& t = cases[k];
    TriangleRasterTarget target;
    target.Reset(camera);
    RasterizeTriangle(camera, Options(CullMode::kNone, near_m), t, 1, &target);
    const Eigen::Vector3d n = (t[1] - t[0]).cross(t[2] - t[0]);
    int drawn = 0;
    for (int row = 0; row < camera.height; ++row) {
      for (int col = 0; col < camera.width; ++col) {
        // The ray's point on the plane and its barycentrics (3D, exact).
        const Eigen::Vector3d d = Ray(camera, col, row);
        const Eigen::Vector3d p = d * (n.dot(t[0]) / n.dot(d));
        const double area = n.squaredNorm();
        const double b1 = n.dot((t[0] - t[2]).cross(p - t[2])) / area;
        const double b2 = n.dot((t[1] - t[0]).cross(p - t[0])) / area;
        const double b0 = 1.0 - b1 - b2;
        const double margin = std::min({b0, b1, b2});
        const bool in_front = p.z() > near_m * (1 + 1e-6);
        const bool clearly_in = margin > 1e-6 && in_front;
        const bool clearly_out = margin < -1e-6 || p.z() < near_m * (1 - 1e-6);
        const bool is_drawn = target.ids.at<int>(row, col) == 1;
        if (clearly_in) {
          ASSERT_TRUE(is_drawn) << "case " << k << " pixel " << col << "," << row;
        }
        if (clearly_out) {
          ASSERT_FALSE(is_drawn) << "case " << k << " pixel " << col << "," << row;
        }
        if (!is_drawn) continue;
        ++drawn;
        EXPECT_GE(1.0 / target.inv_depth.at<float>(row, col), near_m * (1 - 1e-6));
        const Eigen::Vector3d q = Reconstruct(t, target.barycentrics.at<cv::Vec2f>(row, col));
        EXPECT_NEAR((q - p).norm(), 0.0, 1e-5 * std::max(1.0, p.norm())) << "case " << k;
      }
    }
    EXPECT_GT(drawn, 100) << "case " << k;
  }
  // Wholly nearer than the near plane, or behind the camera: nothing.
  TriangleRasterTarget target;
  target.Reset(camera);
  const Triangle too_near = {Eigen::Vector3d(-0.1, 0, 0.4), Eigen::Vector3d(0, 0.1, 0.3), Eigen::Vector3d(0.1, 0, 0.45)};
  const Triangle behind = {Eigen::Vector3d(-1, 0, -2), Eigen::Vector3d(0, 1, -2), Eigen::Vector3d(1, 0, -2)};
  EXPECT_EQ(RasterizeTriangle(camera, Options(CullMode::kNone, near_m), too_near, 2, &target), 0);
  EXPECT_EQ(RasterizeTriangle(camera, Options(CullMode::kNone, near_m), behind, 2, &target), 0);
}

TEST(TriangleRaster, CullsBackOrFrontFacesOnRequest) {
  const PinholeCamera camera = SmallCamera();
  const Triangle front = {Eigen::Vector3d(-0.5, 0.5, 2), Eigen::Vector3d(0.5, 0.5, 2), Eigen::Vector3d(0, -0.5, 2)};
  const Triangle back = {front[0], front[2], front[1]};
  auto written = [&](const Triangle& t, CullMode mode) {
    TriangleRasterTarget target;
    target.Reset(camera);
    return RasterizeTriangle(camera, Options(mode), t, 0, &target);
  };
  const int area = written(front, CullMode::kNone);
  EXPECT_GT(area, 1000);
  EXPECT_EQ(written(front, CullMode::kBack), area);
  EXPECT_EQ(written(front, CullMode::kFront), 0);
  EXPECT_EQ(written(back, CullMode::kBack), 0);
  EXPECT_EQ(written(back, CullMode::kFront), area);
  EXPECT_EQ(written(back, CullMode::kNone), area);
  // Degenerate (collinear) and non-finite triangles draw nothing.
  const Triangle line = {Eigen::Vector3d(0, 0, 2), Eigen::Vector3d(1, 1, 3), Eigen::Vector3d(2, 2, 4)};
  EXPECT_EQ(written(line, CullMode::kNone), 0);
  const Triangle nan = {Eigen::Vector3d(0, 0, 2), Eigen::Vector3d(std::nan(""), 1, 3), Eigen::Vector3d(1, 0, 2)};
  EXPECT_EQ(written(nan, CullMode::kNone), 0);
}

TEST(TriangleRaster, TheNearerOfTwoOverlappingTrianglesWinsAndTiesKeepTheFirst) {
  const PinholeCamera camera = SmallCamera();
  // The far triangle's image contains the near one's.
  const Triangle near_triangle = {camera.Unproject(30, 90, 1.0), camera.Unproject(130, 90, 1.0),
                                  camera.Unproject(80, 20, 1.0)};
  const Triangle far_triangle = {camera.Unproject(10, 110, 3.0), camera.Unproject(150, 110, 3.0),
                                 camera.Unproject(80, 5, 3.0)};
  TriangleRasterTarget alone;
  alone.Reset(camera);
  const int near_area = RasterizeTriangle(camera, Options(CullMode::kBack), near_triangle, 1, &alone);
  alone.Reset(camera);
  const int far_area = RasterizeTriangle(camera, Options(CullMode::kBack), far_triangle, 3, &alone);
  ASSERT_GT(near_area, 1000);
  for (const bool near_first : {true, false}) {
    TriangleRasterTarget target;
    target.Reset(camera);
    const int first = RasterizeTriangle(camera, Options(CullMode::kBack), near_first ? near_triangle : far_triangle,
                                        near_first ? 1 : 3, &target);
    const int second = RasterizeTriangle(camera, Options(CullMode::kBack), near_first ? far_triangle : near_triangle,
                                         near_first ? 3 : 1, &target);
    EXPECT_EQ(first, near_first ? near_area : far_area);
    EXPECT_EQ(second, near_first ? far_area - near_area : near_area);
    EXPECT_EQ(cv::countNonZero(target.ids == 1), near_area);
    EXPECT_EQ(cv::countNonZero(target.ids == 3), far_area - near_area);
    EXPECT_EQ(target.ids.at<int>(60, 80), 1);
    EXPECT_NEAR(target.inv_depth.at<float>(60, 80), 1.0, 1e-6);
  }
  TriangleRasterTarget target;
  target.Reset(camera);
  EXPECT_EQ(RasterizeTriangle(camera, Options(CullMode::kBack), near_triangle, 4, &target), near_area);
  EXPECT_EQ(RasterizeTriangle(camera, Options(CullMode::kBack), near_triangle, 5, &target), 0);
  EXPECT_EQ(target.ids.at<int>(60, 80), 4);
}

TEST(TriangleRaster, BarycentricDerivativesMatchFiniteDifferences) {
  const PinholeCamera camera = SmallCamera();
  const Triangle t = {Eigen::Vector3d(-1.0, -0.8, 2.0), Eigen::Vector3d(0.3, 0.9, 0.7), Eigen::Vector3d(1.2, -0.5, 4.0)};
  const ProjectedTriangle projected(camera, t);
  const double h = 1e-4;
  for (const Eigen::Vector2d& p : {Eigen::Vector2d(80, 60), Eigen::Vector2d(30.5, 70.25), Eigen::Vector2d(120, 20)}) {
    const BarycentricDerivatives d = projected.Derivatives(p.x(), p.y());
    const Eigen::Vector3d dx =
        (projected.Barycentrics(p.x() + h, p.y()) - projected.Barycentrics(p.x() - h, p.y())) / (2 * h);
    const Eigen::Vector3d dy =
        (projected.Barycentrics(p.x(), p.y() + h) - projected.Barycentrics(p.x(), p.y() - h)) / (2 * h);
    EXPECT_NEAR(d.d_dx.x(), dx[1], 1e-7 * std::abs(dx[1]));
    EXPECT_NEAR(d.d_dx.y(), dx[2], 1e-7 * std::abs(dx[2]));
    EXPECT_NEAR(d.d_dy.x(), dy[1], 1e-7 * std::abs(dy[1]));
    EXPECT_NEAR(d.d_dy.y(), dy[2], 1e-7 * std::abs(dy[2]));
    EXPECT_NEAR(projected.Barycentrics(p.x(), p.y()).sum(), 1.0, 1e-12);
    EXPECT_NEAR(1.0 / projected.InverseDepth(p.x(), p.y()), PlaneDepth(camera, t, p.x(), p.y()), 1e-9);
  }
}

// A textured plane (two triangles) seen from two ground-truth poses: the
// surface point view B reports at a pixel, projected into view A, is where
// A's raster reports that same point (A's barycentrics at the nearest pixel,
// moved to the exact position by their derivatives, reconstruct a point
// that projects back onto B's pixel).
TEST(TriangleRaster, TwoViewsOfAPlaneAgreeThroughTheirGroundTruthPoses) {
  const PinholeCamera camera = SmallCamera();
  // A wall 3 m ahead of the origin, 4 m x 3 m, seen from two poses.
  const Eigen::Vector3d c00(-2.0, -1.5, 3.0), c10(2.0, -1.2, 3.4), c11(2.0, 1.5, 3.4), c01(-2.0, 1.5, 3.0);
  const std::vector<Triangle> world = {{c00, c01, c11}, {c00, c11, c10}};
  const Rigid3d world_from_a(Eigen::AngleAxisd(0.05, Eigen::Vector3d::UnitY()).toRotationMatrix(),
                             Eigen::Vector3d(0.1, 0.0, 0.0));
  const Rigid3d world_from_b(
      (Eigen::AngleAxisd(-0.2, Eigen::Vector3d::UnitY()) * Eigen::AngleAxisd(0.07, Eigen::Vector3d::UnitX()))
          .toRotationMatrix(),
      Eigen::Vector3d(0.6, -0.1, 0.4));
  auto render = [&](const Rigid3d& world_from_camera, std::vector<Triangle>* in_camera) {
    const Rigid3d camera_from_world = world_from_camera.Inverse();
    TriangleRasterTarget target;
    target.Reset(camera);
    for (size_t i = 0; i < world.size(); ++i) {
      Triangle t;
      for (int k = 0; k < 3; ++k) t[k] = camera_from_world * world[i][k];
      in_camera->push_back(t);
      RasterizeTriangle(camera, Options(CullMode::kBack), t, static_cast<int>(i), &target);
    }
    return target;
  };
  std::vector<Triangle> in_a, in_b;
  const TriangleRasterTarget a = render(world_from_a, &in_a);
  const TriangleRasterTarget b = render(world_from_b, &in_b);
  const Rigid3d a_from_b = world_from_a.Inverse() * world_from_b;
  const Rigid3d b_from_a = a_from_b.Inverse();
  int checked = 0;
  double worst_px = 0.0;
  for (int row = 0; row < camera.height; row += 3) {
    for (int col = 0; col < camera.width; col += 3) {
      const int id_b = b.ids.at<int>(row, col);
      if (id_b < 0) continue;
      const Eigen::Vector3d point_in_b = Reconstruct(in_b[id_b], b.barycentrics.at<cv::Vec2f>(row, col));
      Eigen::Vector2d in_a_px;
      if (!camera.Project(a_from_b * point_in_b, &in_a_px)) continue;
      const int ca = static_cast<int>(std::lround(in_a_px.x())), ra = static_cast<int>(std::lround(in_a_px.y()));
      if (!camera.InImage(ca, ra) || !camera.InImage(ca + 1, ra + 1) || ca < 1 || ra < 1) continue;
      const int id_a = a.ids.at<int>(ra, ca);
      if (id_a < 0) continue;
      // A's barycentrics at pixel (ca, ra), moved to in_a_px to first order.
      const cv::Vec2f ba = a.barycentrics.at<cv::Vec2f>(ra, ca);
      const BarycentricDerivatives d = ProjectedTriangle(camera, in_a[id_a]).Derivatives(ca, ra);
      const Eigen::Vector2d offset = in_a_px - Eigen::Vector2d(ca, ra);
      const Eigen::Vector2d moved = Eigen::Vector2d(ba[0], ba[1]) + d.d_dx * offset.x() + d.d_dy * offset.y();
      const Eigen::Vector3d point_in_a = Reconstruct(in_a[id_a], cv::Vec2f(moved.x(), moved.y()));
      if (id_a != id_b) continue;  // the point lies near the diagonal, on the other triangle in A
      Eigen::Vector2d back;
      ASSERT_TRUE(camera.Project(b_from_a * point_in_a, &back));
      worst_px = std::max(worst_px, (back - Eigen::Vector2d(col, row)).norm());
      ++checked;
    }
  }
  EXPECT_GT(checked, 500);
  EXPECT_LT(worst_px, 0.01);
}

TEST(TriangleRaster, RejectsInvalidOptions) {
  const PinholeCamera camera = SmallCamera();
  TriangleRasterTarget target;
  target.Reset(camera);
  const Triangle t = {Eigen::Vector3d(0, 0, 2), Eigen::Vector3d(1, 0, 2), Eigen::Vector3d(0, -1, 2)};
  EXPECT_THROW(RasterizeTriangle(camera, Options(CullMode::kBack, 0.0), t, 0, &target), ConfigError);
  EXPECT_THROW(RasterizeTriangle(camera, Options(CullMode::kBack, std::nan("")), t, 0, &target), ConfigError);
  EXPECT_NO_THROW(Options(CullMode::kNone).Check());
}

}  // namespace
}  // namespace duskmap
