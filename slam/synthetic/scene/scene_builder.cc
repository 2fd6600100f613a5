#include "slam/synthetic/scene/scene_builder.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include <opencv2/core.hpp>

#include "slam/core/check.h"
#include "slam/core/random.h"
#include "slam/synthetic/scene/relief.h"

namespace duskmap {
namespace {

// Dimensions of the fittings, metres.
constexpr double kBaseboardHeight = 0.08;
constexpr double kBaseboardDepth = 0.015;
constexpr double kCasingWidth = 0.06;
constexpr double kCasingDepth = 0.015;
constexpr double kWallItemOffset = 0.008;  // hung items stand off the wall (no z-fighting)

const cv::Vec3f kTrimWhite(0.82f, 0.84f, 0.85f);

// A seeded uniform draw in [lo, hi).
double Uniform(cv::RNG& rng, double lo, double hi) { return rng.uniform(lo, hi); }

}  // namespace

WallOpening DoorOpening(double lo, double hi, bool reveal) {
  WallOpening o;
  o.lo = lo;
  o.hi = hi;
  o.z_bottom = 0.0;
  o.z_top = 2.1;
  o.reveal = reveal;
  return o;
}

WallOpening WindowOpening(double lo, double hi, double z_bottom, double z_top) {
  WallOpening o;
  o.lo = lo;
  o.hi = hi;
  o.z_bottom = z_bottom;
  o.z_top = z_top;
  o.window = true;
  o.reveal = true;
  o.depth_m = 0.15;
  return o;
}

SceneBuilder::SceneBuilder(uint64_t seed, std::vector<cv::Mat> user_images, double wall_height_m,
                           double relief_scale)
    : seed_(seed), user_images_(std::move(user_images)), wall_height_m_(wall_height_m),
      relief_scale_(relief_scale) {}

int SceneBuilder::AddQuad(const Eigen::Vector3d& origin, const Eigen::Vector3d& u,
                          const Eigen::Vector3d& v, double su, double sv, int room,
                          TextureKind kind, const cv::Vec3f& color, Emission emission, int lamp) {
  if (su < 1e-3 || sv < 1e-3) return -1;
  Quad q;
  q.origin_in_world = origin;
  q.u_axis = u;
  q.v_axis = v;
  q.size_u_m = su;
  q.size_v_m = sv;
  q.room = room;
  q.emission = emission;
  q.lamp = lamp;
  TextureRequest request;
  request.kind = kind;
  request.size_u_m = su;
  request.size_v_m = sv;
  request.base_bgr = color;
  request.seed = DeriveSeed(seed_, scene_.quads.size());
  request.relief_scale = relief_scale_;
  // Texture columns run along u and rows along v, and u x v is the visible
  // side: seen from the front, u points to the viewer's left. Mirroring the
  // texture makes pictures, posters and text read the right way round; the
  // relief is mirrored with it before its slopes are taken along u and v.
  const SurfaceTexture texture = MakeTexture(request, user_images_, FindPhotoMaterial(photo_materials_, kind));
  cv::flip(texture.albedo, q.albedo, 1);
  if (!texture.height_m.empty()) {
    cv::Mat height_m;
    cv::flip(texture.height_m, height_m, 1);
    q.relief_slope = ReliefSlopes(height_m, su / height_m.cols, sv / height_m.rows);
  }
  scene_.quads.push_back(std::move(q));
  return static_cast<int>(scene_.quads.size()) - 1;
}

int SceneBuilder::AddVertical(const Eigen::Vector2d& center_xy, const Eigen::Vector2d& n,
                              double width, double z_bottom, double z_top, int room,
                              TextureKind kind, const cv::Vec3f& color, Emission emission,
                              int lamp) {
  const Eigen::Vector3d normal(n.x(), n.y(), 0.0);
  const Eigen::Vector3d v(0, 0, -1);
  const Eigen::Vector3d u = v.cross(normal);
  const Eigen::Vector3d origin =
      Eigen::Vector3d(center_xy.x(), center_xy.y(), z_top) - u * (width / 2);
  return AddQuad(origin, u, v, width, z_top - z_bottom, room, kind, color, emission, lamp);
}

int SceneBuilder::AddHorizontal(double x0, double x1, double y0, double y1, double z, bool up,
                                int room, TextureKind kind, const cv::Vec3f& color,
                                Emission emission, int lamp) {
  if (up) {
    return AddQuad({x0, y0, z}, {1, 0, 0}, {0, 1, 0}, x1 - x0, y1 - y0, room, kind, color,
                   emission, lamp);
  }
  return AddQuad({x0, y1, z}, {1, 0, 0}, {0, -1, 0}, x1 - x0, y1 - y0, room, kind, color,
                 emission, lamp);
}

void SceneBuilder::AddBox(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, int room,
                          TextureKind kind, const cv::Vec3f& color, Emission emission, int lamp) {
  const Eigen::Vector2d c = 0.5 * (lo + hi).head<2>();
  AddHorizontal(lo.x(), hi.x(), lo.y(), hi.y(), hi.z(), true, room, kind, color, emission, lamp);
  if (emission != Emission::kNone) {
    AddHorizontal(lo.x(), hi.x(), lo.y(), hi.y(), lo.z(), false, room, kind, color, emission, lamp);
  }
  AddVertical({c.x(), lo.y()}, {0, -1}, hi.x() - lo.x(), lo.z(), hi.z(), room, kind, color, emission, lamp);
  AddVertical({c.x(), hi.y()}, {0, 1}, hi.x() - lo.x(), lo.z(), hi.z(), room, kind, color, emission, lamp);
  AddVertical({lo.x(), c.y()}, {-1, 0}, hi.y() - lo.y(), lo.z(), hi.z(), room, kind, color, emission, lamp);
  AddVertical({hi.x(), c.y()}, {1, 0}, hi.y() - lo.y(), lo.z(), hi.z(), room, kind, color, emission, lamp);
}

void SceneBuilder::AddBoxWithFront(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
                                   const Eigen::Vector2d& front, int room, TextureKind body_kind,
                                   const cv::Vec3f& body_color, TextureKind front_kind,
                                   const cv::Vec3f& front_color) {
  const Eigen::Vector2d c = 0.5 * (lo + hi).head<2>();
  AddHorizontal(lo.x(), hi.x(), lo.y(), hi.y(), hi.z(), true, room, body_kind, body_color);
  const std::pair<Eigen::Vector2d, Eigen::Vector3d> sides[4] = {
      {{0, -1}, {c.x(), lo.y(), hi.x() - lo.x()}},
      {{0, 1}, {c.x(), hi.y(), hi.x() - lo.x()}},
      {{-1, 0}, {lo.x(), c.y(), hi.y() - lo.y()}},
      {{1, 0}, {hi.x(), c.y(), hi.y() - lo.y()}}};
  for (const auto& [n, place] : sides) {
    const bool is_front = n.dot(front) > 0.5;
    AddVertical(place.head<2>(), n, place.z(), lo.z(), hi.z(), room,
                is_front ? front_kind : body_kind, is_front ? front_color : body_color);
  }
}

void SceneBuilder::AddTable(double x0, double x1, double y0, double y1, double height, int room,
                            const cv::Vec3f& color) {
  AddBox({x0, y0, height - 0.04}, {x1, y1, height}, room, TextureKind::kWood, color);
  const double l = 0.05;
  for (const auto& [x, y] : {std::pair{x0, y0}, {x1 - l, y0}, {x0, y1 - l}, {x1 - l, y1 - l}}) {
    AddBox({x + 0.03, y + 0.03, 0.0}, {x + l, y + l, height - 0.04}, room, TextureKind::kWood,
           color * 0.7f);
  }
}

void SceneBuilder::AddChair(const Eigen::Vector2d& center_xy, const Eigen::Vector2d& facing,
                            int room, const cv::Vec3f& color) {
  const double half = 0.21, seat = 0.45, leg = 0.035;
  const Eigen::Vector3d lo(center_xy.x() - half, center_xy.y() - half, seat - 0.04);
  const Eigen::Vector3d hi(center_xy.x() + half, center_xy.y() + half, seat);
  AddBox(lo, hi, room, TextureKind::kFabric, color);
  for (const double sx : {-1.0, 1.0}) {
    for (const double sy : {-1.0, 1.0}) {
      const Eigen::Vector2d p = center_xy + Eigen::Vector2d(sx * (half - leg), sy * (half - leg));
      AddBox({p.x() - leg / 2, p.y() - leg / 2, 0.0}, {p.x() + leg / 2, p.y() + leg / 2, seat - 0.04},
             room, TextureKind::kWood, color * 0.6f);
    }
  }
  // Backrest on the side opposite to `facing`.
  const Eigen::Vector2d back = center_xy - facing * (half - 0.015);
  const Eigen::Vector2d across(std::abs(facing.y()), std::abs(facing.x()));
  const Eigen::Vector2d a = back - across * half - facing.cwiseAbs() * 0.015;
  const Eigen::Vector2d b = back + across * half + facing.cwiseAbs() * 0.015;
  AddBox({std::min(a.x(), b.x()), std::min(a.y(), b.y()), seat},
         {std::max(a.x(), b.x()), std::max(a.y(), b.y()), seat + 0.45}, room, TextureKind::kWood,
         color * 0.6f);
}

void SceneBuilder::AddObjectsOnSurface(double x0, double x1, double y0, double y1, double z,
                                       int count, const Eigen::Vector2d& front, int room) {
  cv::RNG rng(DeriveSeed(seed_ + 0x51, item_counter_++) | 1);
  const bool along_x = (x1 - x0) >= (y1 - y0);
  const double length = along_x ? x1 - x0 : y1 - y0;
  const double depth = along_x ? y1 - y0 : x1 - x0;
  const double slot = length / std::max(1, count);
  for (int i = 0; i < count; ++i) {
    const double width = std::min(slot * 0.85, Uniform(rng, 0.06, 0.3));
    const double object_depth = std::min(depth * 0.9, Uniform(rng, 0.06, 0.3));
    const double height = Uniform(rng, 0.05, 0.35);
    const double start = (along_x ? x0 : y0) + i * slot + Uniform(rng, 0.0, slot - width);
    const double offset = (along_x ? y0 : x0) + Uniform(rng, 0.0, std::max(0.0, depth - object_depth));
    const Eigen::Vector3d lo = along_x ? Eigen::Vector3d(start, offset, z)
                                       : Eigen::Vector3d(offset, start, z);
    const Eigen::Vector3d hi = lo + (along_x ? Eigen::Vector3d(width, object_depth, height)
                                             : Eigen::Vector3d(object_depth, width, height));
    const cv::Vec3f color(rng.uniform(0.05f, 0.8f), rng.uniform(0.05f, 0.8f), rng.uniform(0.05f, 0.8f));
    switch (rng.uniform(0, 4)) {
      case 0:  // plain object (bowl, vase, box)
        AddBox(lo, hi, room, TextureKind::kPaint, color);
        break;
      case 1:  // a small plant
        AddBox(lo, {hi.x(), hi.y(), lo.z() + 0.4 * (hi.z() - lo.z())}, room, TextureKind::kPaint,
               cv::Vec3f(0.2f, 0.3f, 0.55f));
        AddBox({lo.x(), lo.y(), lo.z() + 0.4 * (hi.z() - lo.z())}, hi, room, TextureKind::kFoliage, {});
        break;
      default:  // printed packaging, jar, book
        AddBoxWithFront(lo, hi, front, room, TextureKind::kPackaging, color, TextureKind::kPackaging,
                        color * 1.1f);
    }
  }
}

void SceneBuilder::AddPlant(const Eigen::Vector2d& center_xy, double height_m, int room) {
  const double pot = 0.14, crown = 0.26;
  AddBox({center_xy.x() - pot, center_xy.y() - pot, 0.0}, {center_xy.x() + pot, center_xy.y() + pot, 0.32},
         room, TextureKind::kPaint, cv::Vec3f(0.18f, 0.3f, 0.6f));
  AddBox({center_xy.x() - crown, center_xy.y() - crown, 0.32},
         {center_xy.x() + crown, center_xy.y() + crown, height_m}, room, TextureKind::kFoliage, {});
}

Eigen::Vector2d SceneBuilder::WallPoint(bool axis_x, double plane, double along) const {
  return axis_x ? Eigen::Vector2d(along, plane) : Eigen::Vector2d(plane, along);
}

void SceneBuilder::AddWallBox(bool axis_x, double plane, const Eigen::Vector2d& n, double a,
                              double b, double depth, double z0, double z1, int room,
                              TextureKind kind, const cv::Vec3f& color) {
  const double sign = axis_x ? n.y() : n.x();
  const double near = plane, far = plane + sign * depth;
  const double lo_n = std::min(near, far), hi_n = std::max(near, far);
  const Eigen::Vector3d lo = axis_x ? Eigen::Vector3d(a, lo_n, z0) : Eigen::Vector3d(lo_n, a, z0);
  const Eigen::Vector3d hi = axis_x ? Eigen::Vector3d(b, hi_n, z1) : Eigen::Vector3d(hi_n, b, z1);
  AddBoxWithFront(lo, hi, n, room, kind, color, kind, color);
}

void SceneBuilder::AddWall(bool axis_x, double plane, double lo, double hi,
                           const Eigen::Vector2d& n, int room, std::vector<WallOpening> openings,
                           const WallFinish& finish) {
  const double h = wall_height_m_;
  std::sort(openings.begin(), openings.end(),
            [](const WallOpening& a, const WallOpening& b) { return a.lo < b.lo; });
  auto piece = [&](double a, double b, double zb, double zt) {
    if (b - a > 1e-3 && zt - zb > 1e-3) {
      AddVertical(WallPoint(axis_x, plane, 0.5 * (a + b)), n, b - a, zb, zt, room, finish.kind,
                  finish.color);
    }
  };
  auto baseboard = [&](double a, double b) {
    if (b - a > 0.02) {
      AddWallBox(axis_x, plane, n, a, b, kBaseboardDepth, 0.0, kBaseboardHeight, room,
                 TextureKind::kWood, kTrimWhite);
    }
  };
  // Baseboards run along the wall's foot, stopping at the casings of the
  // openings that reach the floor (doors, passages) and passing under windows.
  double cursor = lo, baseboard_from = lo;
  for (const WallOpening& o : openings) {
    const bool to_floor = o.z_bottom < 0.3;
    piece(cursor, o.lo, 0.0, h);
    piece(o.lo, o.hi, 0.0, o.z_bottom);
    piece(o.lo, o.hi, o.z_top, h);
    if (to_floor) {
      baseboard(baseboard_from, o.lo - (o.casing ? kCasingWidth : 0.0));
      baseboard_from = o.hi + (o.casing ? kCasingWidth : 0.0);
    }
    cursor = o.hi;
    if (o.window) AddWindowGlass(axis_x, plane, n, o, room);
    if (o.reveal) AddReveal(axis_x, plane, n, o, room);
    if (o.casing) AddCasing(axis_x, plane, n, o, room);
  }
  piece(cursor, hi, 0.0, h);
  baseboard(baseboard_from, hi);
}

void SceneBuilder::AddRoomShell(const RoomRect& r, int room,
                                const std::vector<std::vector<WallOpening>>& openings_swne,
                                const std::vector<WallFinish>& walls_swne, TextureKind floor_kind,
                                const cv::Vec3f& floor_color) {
  SLAM_CHECK(openings_swne.size() == 4 && walls_swne.size() == 4);
  AddWall(true, r.y0, r.x0, r.x1, {0, 1}, room, openings_swne[0], walls_swne[0]);
  AddWall(false, r.x0, r.y0, r.y1, {1, 0}, room, openings_swne[1], walls_swne[1]);
  AddWall(true, r.y1, r.x0, r.x1, {0, -1}, room, openings_swne[2], walls_swne[2]);
  AddWall(false, r.x1, r.y0, r.y1, {-1, 0}, room, openings_swne[3], walls_swne[3]);
  AddHorizontal(r.x0, r.x1, r.y0, r.y1, 0.0, true, room, floor_kind, floor_color);
  AddHorizontal(r.x0, r.x1, r.y0, r.y1, wall_height_m_, false, room, TextureKind::kCeiling,
                {0.85f, 0.86f, 0.86f});
}

void SceneBuilder::AddWindowGlass(bool axis_x, double plane, const Eigen::Vector2d& n,
                                  const WallOpening& o, int room) {
  const Eigen::Vector2d center = WallPoint(axis_x, plane, 0.5 * (o.lo + o.hi)) - n * o.depth_m;
  AddVertical(center, n, o.hi - o.lo, o.z_bottom, o.z_top, room, TextureKind::kWindow,
              {1.0f, 1.0f, 1.0f}, Emission::kSky);
}

void SceneBuilder::AddReveal(bool axis_x, double plane, const Eigen::Vector2d& n,
                             const WallOpening& o, int room) {
  const cv::Vec3f white(0.8f, 0.8f, 0.8f);
  const double outer = plane - (axis_x ? n.y() : n.x()) * o.depth_m;
  const double a = std::min(plane, outer), b = std::max(plane, outer);
  auto horizontal = [&](double z, bool up, TextureKind kind, const cv::Vec3f& color) {
    if (axis_x) {
      AddHorizontal(o.lo, o.hi, a, b, z, up, room, kind, color);
    } else {
      AddHorizontal(a, b, o.lo, o.hi, z, up, room, kind, color);
    }
  };
  horizontal(o.z_top, false, TextureKind::kPaint, white);
  if (o.z_bottom > 0.0) {
    horizontal(o.z_bottom, true, TextureKind::kWood, {0.7f, 0.72f, 0.75f});
  } else {
    horizontal(0.0, true, TextureKind::kWoodFloor, {0.2f, 0.32f, 0.45f});
  }
  const double mid = 0.5 * (a + b);
  const Eigen::Vector2d along = axis_x ? Eigen::Vector2d(1, 0) : Eigen::Vector2d(0, 1);
  const Eigen::Vector2d c_lo = axis_x ? Eigen::Vector2d(o.lo, mid) : Eigen::Vector2d(mid, o.lo);
  const Eigen::Vector2d c_hi = axis_x ? Eigen::Vector2d(o.hi, mid) : Eigen::Vector2d(mid, o.hi);
  AddVertical(c_lo, along, b - a, o.z_bottom, o.z_top, room, TextureKind::kPaint, white);
  AddVertical(c_hi, -along, b - a, o.z_bottom, o.z_top, room, TextureKind::kPaint, white);
}

void SceneBuilder::AddCasing(bool axis_x, double plane, const Eigen::Vector2d& n,
                             const WallOpening& o, int room) {
  const double top = std::min(o.z_top + kCasingWidth, wall_height_m_ - 0.01);
  const double bottom = o.window ? std::max(0.0, o.z_bottom - kCasingWidth) : 0.0;
  const cv::Vec3f color = o.window ? kTrimWhite : kTrimWhite * 0.92f;
  AddWallBox(axis_x, plane, n, o.lo - kCasingWidth, o.lo, kCasingDepth, bottom, top, room,
             TextureKind::kWood, color);
  AddWallBox(axis_x, plane, n, o.hi, o.hi + kCasingWidth, kCasingDepth, bottom, top, room,
             TextureKind::kWood, color);
  if (o.z_top + 0.02 < wall_height_m_) {
    AddWallBox(axis_x, plane, n, o.lo, o.hi, kCasingDepth, o.z_top, top, room, TextureKind::kWood,
               color);
  }
  if (o.window) {  // sill, standing out of the wall
    AddWallBox(axis_x, plane, n, o.lo - 0.08, o.hi + 0.08, 0.07, o.z_bottom - 0.03, o.z_bottom,
               room, TextureKind::kWood, kTrimWhite * 0.95f);
  }
}

void SceneBuilder::AddCurtains(bool axis_x, double plane, const Eigen::Vector2d& n,
                               const WallOpening& window, double z_bottom, int room,
                               double panel_width_m) {
  cv::RNG rng(DeriveSeed(seed_ + 0xC7, item_counter_++) | 1);
  const cv::Vec3f color(rng.uniform(0.15f, 0.7f), rng.uniform(0.15f, 0.7f), rng.uniform(0.15f, 0.7f));
  const double top = std::min(window.z_top + 0.2, wall_height_m_ - 0.04);
  const double offset = 0.09;
  const double width = panel_width_m;
  for (const double center : {window.lo - kCasingWidth - width / 2 + 0.08,
                              window.hi + kCasingWidth + width / 2 - 0.08}) {
    AddVertical(WallPoint(axis_x, plane, center) + n * offset, n, width, z_bottom, top, room,
                TextureKind::kCurtain, color);
  }
  // The rod.
  AddWallBox(axis_x, plane, n, window.lo - 0.3, window.hi + 0.3, offset + 0.02, top, top + 0.025,
             room, TextureKind::kPaint, cv::Vec3f(0.12f, 0.12f, 0.12f));
}

void SceneBuilder::AddRadiator(bool axis_x, double plane, const Eigen::Vector2d& n, double along,
                               double width, int room) {
  const double sign = axis_x ? n.y() : n.x();
  const double near = plane + sign * 0.03, far = plane + sign * 0.11;
  const double lo_n = std::min(near, far), hi_n = std::max(near, far);
  const double a = along - width / 2, b = along + width / 2;
  const Eigen::Vector3d lo = axis_x ? Eigen::Vector3d(a, lo_n, 0.14) : Eigen::Vector3d(lo_n, a, 0.14);
  const Eigen::Vector3d hi = axis_x ? Eigen::Vector3d(b, hi_n, 0.66) : Eigen::Vector3d(hi_n, b, 0.66);
  AddBoxWithFront(lo, hi, n, room, TextureKind::kPaint, kTrimWhite, TextureKind::kRadiator, kTrimWhite);
}

void SceneBuilder::AddSwitch(bool axis_x, double plane, const Eigen::Vector2d& n, double along,
                             double z, int room) {
  AddWallItem(axis_x, plane, n, along, 0.08, z, z + 0.12, room, TextureKind::kSwitch);
}

int SceneBuilder::AddWallItem(bool axis_x, double plane, const Eigen::Vector2d& n, double along,
                              double width, double z_bottom, double z_top, int room,
                              TextureKind kind, const cv::Vec3f& color) {
  return AddVertical(WallPoint(axis_x, plane, along) + n * kWallItemOffset, n, width, z_bottom,
                     z_top, room, kind, color);
}

}  // namespace duskmap
