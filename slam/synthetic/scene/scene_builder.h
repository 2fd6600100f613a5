// Building blocks for the synthetic apartment: textured quads, boxes, room
// shells with openings (windows, doors) and the small fittings a lived-in
// home has (baseboards, door casings, sills, curtains, radiators, switches,
// chairs, objects standing on a surface). Every quad gets a seeded
// procedural texture, so the same calls give the same scene.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "slam/synthetic/scene/photo_materials.h"
#include "slam/synthetic/scene/scene.h"
#include "slam/synthetic/scene/textures.h"

namespace duskmap {

// An opening in a wall, in the wall's own coordinates.
struct WallOpening {
  double lo = 0.0, hi = 0.0;  // world coordinate along the wall (x or y)
  double z_bottom = 0.0, z_top = 0.0;
  bool window = false;
  bool reveal = false;    // add jambs, head and sill/threshold (once per opening)
  double depth_m = 0.1;   // reveal depth (wall thickness)
  bool casing = true;     // a trim frame around it on this side of the wall
};

WallOpening DoorOpening(double lo, double hi, bool reveal);
WallOpening WindowOpening(double lo, double hi, double z_bottom, double z_top);

struct RoomRect {
  double x0 = 0.0, x1 = 0.0, y0 = 0.0, y1 = 0.0;
};

struct WallFinish {
  TextureKind kind = TextureKind::kPaint;
  cv::Vec3f color = cv::Vec3f(0.6f, 0.6f, 0.6f);
};

class SceneBuilder {
 public:
  // relief_scale multiplies every material's relief heights (relief.h); 0 = flat.
  SceneBuilder(uint64_t seed, std::vector<cv::Mat> user_images, double wall_height_m,
               double relief_scale = 0.0);

  Scene& scene() { return scene_; }
  // Quads added from now on whose kind has a material here draw it
  // (photo_materials.h) instead of the procedural texture.
  void SetPhotoMaterials(std::vector<PhotoMaterial> materials) { photo_materials_ = std::move(materials); }
  double wall_height_m() const { return wall_height_m_; }

  // A textured rectangle origin + s u + t v, s in [0, su], t in [0, sv];
  // u x v is the visible side. Returns its index, or -1 when degenerate.
  int AddQuad(const Eigen::Vector3d& origin, const Eigen::Vector3d& u, const Eigen::Vector3d& v,
              double su, double sv, int room, TextureKind kind, const cv::Vec3f& color,
              Emission emission = Emission::kNone, int lamp = -1);

  // Vertical rectangle whose plane passes through center_xy with horizontal
  // normal n (the visible side), spanning `width` along the plane.
  int AddVertical(const Eigen::Vector2d& center_xy, const Eigen::Vector2d& n, double width,
                  double z_bottom, double z_top, int room, TextureKind kind,
                  const cv::Vec3f& color, Emission emission = Emission::kNone, int lamp = -1);

  int AddHorizontal(double x0, double x1, double y0, double y1, double z, bool up, int room,
                    TextureKind kind, const cv::Vec3f& color, Emission emission = Emission::kNone,
                    int lamp = -1);

  // An axis-aligned box: top and four sides (and the bottom when emissive).
  void AddBox(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, int room, TextureKind kind,
              const cv::Vec3f& color, Emission emission = Emission::kNone, int lamp = -1);

  // A box whose side facing `front` (a unit axis direction in the floor
  // plane) has its own texture: cabinets, appliances, packaging.
  void AddBoxWithFront(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
                       const Eigen::Vector2d& front, int room, TextureKind body_kind,
                       const cv::Vec3f& body_color, TextureKind front_kind,
                       const cv::Vec3f& front_color);

  void AddTable(double x0, double x1, double y0, double y1, double height, int room,
                const cv::Vec3f& color);

  // A chair standing at center_xy whose seat faces `facing` (its back on the
  // opposite side).
  void AddChair(const Eigen::Vector2d& center_xy, const Eigen::Vector2d& facing, int room,
                const cv::Vec3f& color);

  // Small objects (boxes with printed or plain surfaces) standing in a row on
  // a horizontal surface at height z, inside [x0, x1] x [y0, y1], `count` of
  // them, their printed sides facing `front`.
  void AddObjectsOnSurface(double x0, double x1, double y0, double y1, double z, int count,
                           const Eigen::Vector2d& front, int room);

  // A potted plant: pot plus a leafy crown, standing at center_xy.
  void AddPlant(const Eigen::Vector2d& center_xy, double height_m, int room);

  // One wall of a room. `axis_x`: the wall runs along x (south/north walls)
  // at y = plane, else along y at x = plane; n is the normal into the room.
  // Adds baseboards along the wall and casings around the openings.
  void AddWall(bool axis_x, double plane, double lo, double hi, const Eigen::Vector2d& n, int room,
               std::vector<WallOpening> openings, const WallFinish& finish);

  // Floor, ceiling and the four walls (south, west, north, east order).
  void AddRoomShell(const RoomRect& r, int room,
                    const std::vector<std::vector<WallOpening>>& openings_swne,
                    const std::vector<WallFinish>& walls_swne, TextureKind floor_kind,
                    const cv::Vec3f& floor_color);

  // Fabric curtains hanging on both sides of a window opening on a wall at
  // `plane` with room-side normal n, from just above the window to z_bottom.
  void AddCurtains(bool axis_x, double plane, const Eigen::Vector2d& n, const WallOpening& window,
                   double z_bottom, int room, double panel_width_m = 0.34);

  // A radiator on the wall below a window (centre `along`, width `width`).
  void AddRadiator(bool axis_x, double plane, const Eigen::Vector2d& n, double along, double width,
                   int room);

  // A switch or socket plate on the wall.
  void AddSwitch(bool axis_x, double plane, const Eigen::Vector2d& n, double along, double z,
                 int room);

  // A flat item hung on the wall (picture, poster, clock, calendar...).
  int AddWallItem(bool axis_x, double plane, const Eigen::Vector2d& n, double along, double width,
                  double z_bottom, double z_top, int room, TextureKind kind,
                  const cv::Vec3f& color = cv::Vec3f(0.5f, 0.5f, 0.5f));

 private:
  Eigen::Vector2d WallPoint(bool axis_x, double plane, double along) const;
  void AddWindowGlass(bool axis_x, double plane, const Eigen::Vector2d& n, const WallOpening& o,
                      int room);
  void AddReveal(bool axis_x, double plane, const Eigen::Vector2d& n, const WallOpening& o,
                 int room);
  void AddCasing(bool axis_x, double plane, const Eigen::Vector2d& n, const WallOpening& o,
                 int room);
  // An axis-aligned box against a wall: spans [a, b] along the wall, `depth`
  // into the room from the wall plane, [z0, z1] in height.
  void AddWallBox(bool axis_x, double plane, const Eigen::Vector2d& n, double a, double b,
                  double depth, double z0, double z1, int room, TextureKind kind,
                  const cv::Vec3f& color);

  uint64_t seed_;
  std::vector<cv::Mat> user_images_;
  std::vector<PhotoMaterial> photo_materials_;
  double wall_height_m_;
  double relief_scale_;
  Scene scene_;
  uint64_t item_counter_ = 0;  // seeds the sizes and colours of generated items
};

}  // namespace duskmap
