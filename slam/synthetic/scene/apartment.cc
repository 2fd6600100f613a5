#include "slam/synthetic/scene/apartment.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <random>

#include "slam/core/check.h"
#include "slam/core/random.h"
#include "slam/synthetic/scene/scene_builder.h"
#include "slam/synthetic/scene/textures.h"

namespace duskmap {
namespace {

constexpr double kPi = 3.14159265358979323846;

int AddLamp(Scene& scene, const std::string& name, const Eigen::Vector3d& p, int room, double cd,
            const std::string& on_from) {
  scene.lamps.push_back({name, p, room, cd, on_from});
  return static_cast<int>(scene.lamps.size()) - 1;
}

// A ceiling light on in every session: the lamp 0.25 m below the ceiling
// above `xy`, in a glowing 0.3 m fixture (`cd` before lamps.intensity_scale).
void AddCeilingLight(SceneBuilder& b, const std::string& name, const Eigen::Vector2d& xy, int room,
                     double cd, const ApartmentOptions& options) {
  const double z = options.wall_height_m - 0.25;
  const int lamp = AddLamp(b.scene(), name, {xy.x(), xy.y(), z}, room, cd * options.lamps.intensity_scale, "");
  b.AddBox({xy.x() - 0.15, xy.y() - 0.15, z + 0.05}, {xy.x() + 0.15, xy.y() + 0.15, z + 0.2}, room,
           TextureKind::kLampShade, {0.55f, 0.75f, 0.85f}, Emission::kLamp, lamp);
}

// A lamp shade glowing around lamp `lamp` (a box centred on its position).
void AddShade(SceneBuilder& b, int lamp, const Eigen::Vector3d& half_size) {
  const Lamp& l = b.scene().lamps[static_cast<size_t>(lamp)];
  b.AddBox(l.position_in_world - half_size, l.position_in_world + half_size, l.room,
           TextureKind::kLampShade, {0.55f, 0.75f, 0.85f}, Emission::kLamp, lamp);
}

WallFinish Paint(const cv::Vec3f& color) { return {TextureKind::kPaint, color}; }

// The walls of `room`: its own colour, or with options.wall_paint_seed a
// plausible paint (BGR reflectance) drawn for it.
cv::Vec3f WallColor(const ApartmentOptions& options, int room, const cv::Vec3f& own_bgr) {
  if (options.wall_paint_seed == 0) return own_bgr;
  static const cv::Vec3f kPaints[] = {
      {0.62f, 0.68f, 0.70f}, {0.55f, 0.72f, 0.78f}, {0.55f, 0.62f, 0.66f}, {0.72f, 0.64f, 0.52f},
      {0.50f, 0.64f, 0.52f}, {0.50f, 0.60f, 0.70f}, {0.62f, 0.60f, 0.76f}, {0.40f, 0.50f, 0.70f},
      {0.62f, 0.72f, 0.58f}, {0.72f, 0.58f, 0.62f}, {0.70f, 0.70f, 0.68f}, {0.45f, 0.52f, 0.56f}};
  Rng rng(DeriveSeed(options.wall_paint_seed, static_cast<uint64_t>(room)));
  const size_t pick = std::uniform_int_distribution<size_t>(0, std::size(kPaints) - 1)(rng);
  const float lightness = std::uniform_real_distribution<float>(0.85f, 1.1f)(rng);
  const cv::Vec3f paint = kPaints[pick] * lightness;
  return {std::min(paint[0], 0.85f), std::min(paint[1], 0.85f), std::min(paint[2], 0.85f)};
}

RoomRect ShellRect(int room) {
  const RoomFloor floor = ApartmentRoomFloors()[static_cast<size_t>(room)];
  return {floor.min_xy.x(), floor.max_xy.x(), floor.min_xy.y(), floor.max_xy.y()};
}

void AddLivingRoom(SceneBuilder& b, const ApartmentOptions& options) {
  Scene& s = b.scene();
  const int room = 0;
  const WallFinish paint = Paint(WallColor(options, room, {0.62f, 0.68f, 0.70f}));  // warm off-white (BGR)
  const WallOpening patio = WindowOpening(2.0, 4.2, 0.4, 2.2);
  const WallOpening west_a = WindowOpening(0.7, 1.9, 0.8, 2.2);
  const WallOpening west_b = WindowOpening(2.7, 3.9, 0.8, 2.2);
  WallOpening kitchen_passage{1.2, 3.6, 0.0, 2.2, false, true, 0.1};
  b.AddRoomShell(ShellRect(room), room,
                 {{patio}, {west_a, west_b}, {DoorOpening(4.7, 5.6, true)}, {kitchen_passage}},
                 {paint, paint, paint, paint}, TextureKind::kWoodFloor, {0.22f, 0.36f, 0.52f});
  // North wall: the docking picture above the sofa, a clock, a poster.
  s.docking_picture = b.AddVertical({1.7, 4.59}, {0, -1}, 1.4, 1.15, 2.05, room, TextureKind::kDocking, {});
  b.AddWallItem(true, 4.6, {0, -1}, 2.85, 0.3, 1.65, 1.95, room, TextureKind::kClock);
  b.AddVertical({3.6, 4.59}, {0, -1}, 0.7, 1.2, 1.9, room, TextureKind::kPoster, {});
  b.AddSwitch(true, 4.6, {0, -1}, 4.55, 1.05, room);
  // Sofa with cushions, rug, coffee table with magazines and a bowl.
  if (options.box_furniture) {
    b.AddBox({0.6, 3.75, 0.0}, {2.8, 4.6, 0.45}, room, TextureKind::kFabric, {0.35f, 0.25f, 0.2f});
    b.AddBox({0.6, 4.3, 0.45}, {2.8, 4.58, 0.85}, room, TextureKind::kFabric, {0.33f, 0.24f, 0.19f});
    for (const double x : {0.7, 1.35, 2.0}) {
      b.AddBox({x, 4.08, 0.45}, {x + 0.5, 4.3, 0.8}, room, TextureKind::kCurtain, {0.5f, 0.45f, 0.3f});
    }
  }
  b.AddBox({0.7, 2.5, 0.0}, {2.9, 3.7, 0.006}, room, TextureKind::kRug, {0.15f, 0.2f, 0.45f});
  b.AddBox({1.1, 2.95, 0.0}, {2.3, 3.5, 0.42}, room, TextureKind::kWood, {0.1f, 0.18f, 0.3f});
  b.AddObjectsOnSurface(1.2, 2.2, 3.0, 3.45, 0.42, 3, {0, -1}, room);
  b.AddPlant({0.32, 4.28}, 1.25, room);
  // South wall: TV on its stand, a picture above, the patio window with
  // curtains, a plant, the bookshelf.
  if (options.box_furniture) {
    b.AddBoxWithFront({0.2, 0.0, 0.0}, {1.6, 0.45, 0.5}, {0, 1}, room, TextureKind::kWood,
                      {0.12f, 0.14f, 0.16f}, TextureKind::kCabinet, {0.14f, 0.16f, 0.18f});
    b.AddBoxWithFront({0.35, 0.12, 0.52}, {1.3, 0.17, 1.08}, {0, 1}, room, TextureKind::kPaint,
                      {0.03f, 0.03f, 0.03f}, TextureKind::kScreen, {});
    b.AddBox({0.75, 0.1, 0.5}, {0.9, 0.2, 0.52}, room, TextureKind::kPaint, {0.03f, 0.03f, 0.03f});
  }
  b.AddObjectsOnSurface(1.32, 1.58, 0.05, 0.4, 0.5, 1, {0, 1}, room);
  b.AddWallItem(true, 0.0, {0, 1}, 0.82, 0.6, 1.45, 1.9, room, TextureKind::kPicture);
  b.AddCurtains(true, 0.0, {0, 1}, patio, 0.0, room, 0.2);
  b.AddPlant({4.05, 0.45}, 1.1, room);
  if (options.box_furniture) {
    b.AddBox({4.4, 0.0, 0.0}, {5.9, 0.35, 2.0}, room, TextureKind::kBooks, {});
  }
  // West wall: radiators and curtains at both windows, the table-lamp cabinet
  // and a small clock between them.
  for (const WallOpening& w : {west_a, west_b}) {
    b.AddRadiator(false, 0.0, {1, 0}, 0.5 * (w.lo + w.hi), 0.9, room);
    b.AddCurtains(false, 0.0, {1, 0}, w, 0.7, room);
  }
  b.AddBoxWithFront({0.0, 2.0, 0.0}, {0.45, 2.6, 0.6}, {1, 0}, room, TextureKind::kWood,
                    {0.12f, 0.12f, 0.14f}, TextureKind::kCabinet, {0.14f, 0.14f, 0.16f});
  b.AddWallItem(false, 0.0, {1, 0}, 2.3, 0.14, 1.6, 1.74, room, TextureKind::kClock);
  b.AddBox({0.18, 2.26, 0.6}, {0.26, 2.34, 0.7}, room, TextureKind::kPaint, {0.1f, 0.1f, 0.1f});
  b.AddObjectsOnSurface(0.05, 0.4, 2.44, 2.58, 0.6, 1, {1, 0}, room);
  const int table_lamp = AddLamp(s, "living table lamp", {0.22, 2.3, 0.85}, room,
                                 35.0 * options.lamps.intensity_scale, "");
  AddShade(b, table_lamp, {0.1, 0.1, 0.11});
  // Dining table with a bowl and three chairs.
  if (options.box_furniture) {
    b.AddTable(3.9, 5.1, 2.2, 3.0, 0.76, room, {0.15f, 0.3f, 0.45f});
    b.AddObjectsOnSurface(4.0, 5.0, 2.3, 2.9, 0.76, 3, {0, -1}, room);
    b.AddChair({4.2, 3.2}, {0, -1}, room, {0.2f, 0.25f, 0.35f});
    b.AddChair({4.8, 3.2}, {0, -1}, room, {0.2f, 0.25f, 0.35f});
    b.AddChair({5.35, 2.6}, {-1, 0}, room, {0.2f, 0.25f, 0.35f});
  }
  // East wall pieces beside the kitchen passage.
  b.AddVertical({5.99, 4.1}, {-1, 0}, 0.7, 1.1, 2.0, room, TextureKind::kPoster, {});
  b.AddVertical({5.99, 0.6}, {-1, 0}, 0.8, 1.2, 1.8, room, TextureKind::kPicture, {});
  b.AddSwitch(false, 6.0, {-1, 0}, 1.0, 1.05, room);
  // Floor lamp (on from the configured time).
  const int floor_lamp = AddLamp(s, "living floor lamp", {5.6, 4.2, 1.6}, room,
                                 120.0 * options.lamps.intensity_scale, options.lamps.living_lamp_on_from);
  b.AddBox({5.58, 4.18, 0.0}, {5.62, 4.22, 1.45}, room, TextureKind::kWood, {0.05f, 0.05f, 0.05f});
  AddShade(b, floor_lamp, {0.15, 0.15, 0.15});
  if (options.lamps.living_ceiling_cd > 0.0) {
    AddCeilingLight(b, "living ceiling", {3.0, 2.6}, room, options.lamps.living_ceiling_cd, options);
  }
}

void AddKitchen(SceneBuilder& b, const ApartmentOptions& options) {
  Scene& s = b.scene();
  const int room = 1;
  const WallFinish paint = Paint(WallColor(options, room, {0.55f, 0.72f, 0.78f}));  // pale yellow
  const WallOpening window = WindowOpening(7.3, 8.9, 1.0, 2.1);
  WallOpening passage{1.2, 3.6, 0.0, 2.2, false, false, 0.1};
  passage.casing = false;
  b.AddRoomShell(ShellRect(room), room, {{window}, {passage}, {DoorOpening(7.0, 7.9, true)}, {}},
                 {paint, paint, paint, paint}, TextureKind::kTiles, {0.35f, 0.38f, 0.4f});
  // Counter along the east wall: base and wall cabinets, worktop, tiled
  // backsplash, appliances and utensils.
  const cv::Vec3f cabinet(0.3f, 0.45f, 0.55f);
  b.AddBoxWithFront({9.4, 0.3, 0.0}, {10.0, 4.2, 0.86}, {-1, 0}, room, TextureKind::kWood, cabinet,
                    TextureKind::kCabinet, cabinet);
  b.AddBox({9.38, 0.3, 0.86}, {10.0, 4.2, 0.9}, room, TextureKind::kCounter, {0.12f, 0.13f, 0.14f});
  b.AddBoxWithFront({9.65, 0.3, 1.5}, {10.0, 4.2, 2.2}, {-1, 0}, room, TextureKind::kWood, cabinet,
                    TextureKind::kCabinet, cabinet);
  b.AddWallItem(false, 10.0, {-1, 0}, 2.25, 3.9, 0.9, 1.5, room, TextureKind::kTiles, {0.8f, 0.8f, 0.78f});
  b.AddObjectsOnSurface(9.45, 9.95, 0.35, 3.3, 0.9, 9, {-1, 0}, room);
  b.AddBoxWithFront({9.5, 3.4, 0.9}, {9.95, 3.95, 1.2}, {-1, 0}, room, TextureKind::kPaint,
                    {0.7f, 0.7f, 0.7f}, TextureKind::kScreen, {});
  b.AddVertical({9.99, 4.45}, {-1, 0}, 0.25, 1.0, 1.4, room, TextureKind::kPicture, {});
  // Fridge with notes and magnets on its door.
  b.AddBoxWithFront({6.15, 3.9, 0.0}, {6.85, 4.55, 1.8}, {0, -1}, room, TextureKind::kPaint,
                    {0.8f, 0.8f, 0.8f}, TextureKind::kCabinet, {0.82f, 0.82f, 0.82f});
  {
    cv::RNG rng(DeriveSeed(options.seed, 0xF1D6E));
    for (int i = 0; i < 7; ++i) {
      const double x = rng.uniform(6.22, 6.72), z = rng.uniform(0.9, 1.65);
      const double w = rng.uniform(0.05, 0.13), h = rng.uniform(0.05, 0.15);
      b.AddVertical({x + w / 2, 3.893 - 0.001 * i}, {0, -1}, w, z, z + h, room,
                    TextureKind::kPackaging, {rng.uniform(0.3f, 0.9f), rng.uniform(0.3f, 0.9f), rng.uniform(0.3f, 0.9f)});
    }
  }
  // Table, two chairs, a bowl.
  if (options.box_furniture) {
    b.AddTable(7.3, 8.5, 1.6, 2.6, 0.76, room, {0.2f, 0.35f, 0.5f});
    b.AddObjectsOnSurface(7.4, 8.4, 1.7, 2.5, 0.76, 3, {0, -1}, room);
    b.AddChair({7.05, 2.1}, {1, 0}, room, {0.3f, 0.2f, 0.15f});
    b.AddChair({7.9, 2.85}, {0, -1}, room, {0.3f, 0.2f, 0.15f});
  }
  // South wall: window with curtains and a radiator, a spice shelf, a poster.
  b.AddCurtains(true, 0.0, {0, 1}, window, 0.9, room, 0.25);
  b.AddRadiator(true, 0.0, {0, 1}, 8.1, 1.0, room);
  b.AddBox({6.3, 0.0, 1.42}, {7.1, 0.2, 1.45}, room, TextureKind::kWood, {0.2f, 0.3f, 0.4f});
  b.AddObjectsOnSurface(6.32, 7.08, 0.01, 0.19, 1.45, 4, {0, 1}, room);
  b.AddWallItem(true, 0.0, {0, 1}, 9.35, 0.5, 1.1, 1.8, room, TextureKind::kPoster);
  // West wall: a calendar; north wall: poster, clock, switch; a bin.
  b.AddWallItem(false, 6.1, {1, 0}, 0.6, 0.35, 1.2, 1.7, room, TextureKind::kPackaging, {0.85f, 0.85f, 0.85f});
  b.AddVertical({8.75, 4.59}, {0, -1}, 0.9, 1.2, 1.9, room, TextureKind::kPoster, {});
  b.AddWallItem(true, 4.6, {0, -1}, 9.5, 0.28, 1.6, 1.88, room, TextureKind::kClock);
  b.AddSwitch(true, 4.6, {0, -1}, 6.87, 1.05, room);
  b.AddBox({6.2, 0.15, 0.0}, {6.5, 0.45, 0.45}, room, TextureKind::kPaint, {0.25f, 0.3f, 0.3f});
  const int lamp = AddLamp(s, "kitchen ceiling", {8.0, 2.3, 2.25}, room, 110.0 * options.lamps.intensity_scale, "");
  b.AddBox({7.85, 2.15, 2.3}, {8.15, 2.45, 2.45}, room, TextureKind::kLampShade, {0.55f, 0.75f, 0.85f},
           Emission::kLamp, lamp);
}

void AddCorridor(SceneBuilder& b, const ApartmentOptions& options) {
  Scene& s = b.scene();
  const int room = 2;
  const WallFinish paint = Paint(WallColor(options, room, {0.55f, 0.62f, 0.66f}));
  b.AddRoomShell(ShellRect(room), room,
                 {{DoorOpening(4.7, 5.6, false), DoorOpening(7.0, 7.9, false)}, {},
                  {DoorOpening(2.0, 2.9, true)}, {}},
                 {paint, paint, paint, paint}, TextureKind::kWoodFloor, {0.2f, 0.32f, 0.45f});
  // Closed doors (bathroom, entrance) with what people hang on them, and a doormat.
  b.AddVertical({7.9, 5.89}, {0, -1}, 0.8, 0.0, 2.05, room, TextureKind::kDoor, {0.8f, 0.8f, 0.78f});
  b.AddVertical({7.95, 5.885}, {0, -1}, 0.36, 1.25, 1.75, room, TextureKind::kPoster, {});
  b.AddBox({7.6, 5.82, 1.0}, {7.9, 5.885, 1.55}, room, TextureKind::kCurtain, {0.6f, 0.35f, 0.25f});
  b.AddVertical({9.99, 5.3}, {-1, 0}, 0.9, 0.0, 2.05, room, TextureKind::kDoor, {0.3f, 0.4f, 0.5f});
  b.AddVertical({9.985, 5.25}, {-1, 0}, 0.45, 1.2, 1.8, room, TextureKind::kPoster, {});
  b.AddBox({9.2, 4.85, 0.0}, {9.9, 5.55, 0.012}, room, TextureKind::kRug, {0.1f, 0.25f, 0.3f});
  b.AddBox({0.8, 5.08, 0.0}, {9.2, 5.52, 0.006}, room, TextureKind::kRug, {0.2f, 0.15f, 0.35f});
  // North wall: coat rack with coats over a shoe cabinet, a gallery of frames.
  b.AddBoxWithFront({0.2, 5.6, 0.0}, {1.2, 5.9, 0.4}, {0, -1}, room, TextureKind::kWood,
                    {0.2f, 0.25f, 0.3f}, TextureKind::kCabinet, {0.22f, 0.27f, 0.32f});
  b.AddBox({0.2, 5.85, 1.64}, {1.2, 5.9, 1.72}, room, TextureKind::kWood, {0.15f, 0.2f, 0.25f});
  {
    cv::RNG rng(DeriveSeed(options.seed, 0xC0A7));
    double x = 0.24;
    while (x < 1.1) {
      const double w = rng.uniform(0.22, 0.32);
      b.AddBox({x, 5.66, rng.uniform(0.8, 1.05)}, {std::min(x + w, 1.18), 5.85, 1.66}, room,
               TextureKind::kCurtain, {rng.uniform(0.05f, 0.5f), rng.uniform(0.05f, 0.5f), rng.uniform(0.05f, 0.5f)});
      x += w + 0.03;
    }
  }
  b.AddObjectsOnSurface(0.25, 1.15, 5.4, 5.58, 0.0, 3, {0, -1}, room);  // shoes
  b.AddSwitch(true, 5.9, {0, -1}, 1.85, 1.05, room);
  b.AddVertical({4.2, 5.89}, {0, -1}, 0.6, 1.2, 1.8, room, TextureKind::kPicture, {});
  b.AddVertical({6.5, 5.89}, {0, -1}, 0.5, 1.3, 1.9, room, TextureKind::kPoster, {});
  b.AddWallItem(true, 5.9, {0, -1}, 3.2, 0.3, 1.5, 1.8, room, TextureKind::kPicture);
  b.AddWallItem(true, 5.9, {0, -1}, 5.0, 0.35, 1.2, 1.6, room, TextureKind::kPicture);
  b.AddWallItem(true, 5.9, {0, -1}, 5.5, 0.25, 1.45, 1.75, room, TextureKind::kPoster);
  b.AddWallItem(true, 5.9, {0, -1}, 8.8, 0.4, 1.2, 1.7, room, TextureKind::kPicture);
  // South wall: pictures, a console table between the doors, switches.
  b.AddVertical({1.2, 4.71}, {0, 1}, 0.8, 1.2, 1.8, room, TextureKind::kPicture, {});
  b.AddVertical({3.4, 4.71}, {0, 1}, 0.6, 1.1, 1.9, room, TextureKind::kPoster, {});
  b.AddVertical({9.0, 4.71}, {0, 1}, 0.6, 1.2, 1.8, room, TextureKind::kPicture, {});
  b.AddBoxWithFront({5.85, 4.7, 0.0}, {6.75, 5.02, 0.8}, {0, 1}, room, TextureKind::kWood,
                    {0.15f, 0.22f, 0.3f}, TextureKind::kCabinet, {0.15f, 0.22f, 0.3f});
  b.AddObjectsOnSurface(5.9, 6.7, 4.74, 4.98, 0.8, 3, {0, 1}, room);
  b.AddWallItem(true, 4.7, {0, 1}, 6.3, 0.5, 1.3, 1.8, room, TextureKind::kPicture);
  b.AddSwitch(true, 4.7, {0, 1}, 4.55, 1.05, room);
  b.AddSwitch(true, 4.7, {0, 1}, 6.87, 1.05, room);
  // By the bedroom door: a calendar and a key box.
  b.AddWallItem(true, 4.7, {0, 1}, 2.2, 0.4, 1.15, 1.75, room, TextureKind::kPackaging, {0.85f, 0.85f, 0.85f});
  b.AddBoxWithFront({2.6, 4.7, 1.3}, {2.95, 4.78, 1.6}, {0, 1}, room, TextureKind::kWood,
                    {0.2f, 0.3f, 0.4f}, TextureKind::kPackaging, {0.3f, 0.45f, 0.55f});
  // West end: poster over a radiator; east end: dresser with objects.
  b.AddVertical({0.01, 5.3}, {1, 0}, 0.6, 1.1, 1.9, room, TextureKind::kPoster, {});
  b.AddRadiator(false, 0.0, {1, 0}, 5.3, 0.7, room);
  b.AddBoxWithFront({9.1, 5.6, 0.0}, {9.9, 5.9, 1.0}, {0, -1}, room, TextureKind::kWood,
                    {0.25f, 0.3f, 0.35f}, TextureKind::kCabinet, {0.25f, 0.3f, 0.35f});
  b.AddObjectsOnSurface(9.15, 9.85, 5.63, 5.87, 1.0, 3, {0, -1}, room);
  for (double x : {2.5, 7.5}) {
    const int lamp = AddLamp(s, "corridor ceiling", {x, 5.3, 2.3}, room, 70.0 * options.lamps.intensity_scale, "");
    b.AddBox({x - 0.12, 5.18, 2.38}, {x + 0.12, 5.42, 2.48}, room, TextureKind::kLampShade,
             {0.55f, 0.75f, 0.85f}, Emission::kLamp, lamp);
  }
}

void AddBedroom(SceneBuilder& b, const ApartmentOptions& options) {
  Scene& s = b.scene();
  const int room = 3;
  const WallFinish paint = Paint(WallColor(options, room, {0.5f, 0.62f, 0.72f}));
  const WallFinish wallpaper{TextureKind::kWallpaper, WallColor(options, 4, {0.55f, 0.66f, 0.74f})};
  const WallOpening window = WindowOpening(6.9, 8.1, 0.9, 2.1);
  b.AddRoomShell(ShellRect(room), room, {{DoorOpening(2.0, 2.9, false)}, {window}, {}, {}},
                 {paint, paint, wallpaper, paint}, TextureKind::kWoodFloor, {0.25f, 0.38f, 0.5f});
  // Bed with duvet and pillows, headboard, bedside table with the lamp.
  if (options.box_furniture) {
    b.AddBox({2.4, 7.0, 0.0}, {4.4, 9.0, 0.55}, room, TextureKind::kFabric, {0.55f, 0.45f, 0.4f});
    b.AddHorizontal(2.45, 4.35, 7.05, 8.4, 0.553, true, room, TextureKind::kCurtain, {0.6f, 0.5f, 0.45f});
    for (const double x : {2.55, 3.55}) {
      b.AddBox({x, 8.5, 0.55}, {x + 0.7, 8.88, 0.7}, room, TextureKind::kFabric, {0.75f, 0.75f, 0.72f});
    }
    b.AddBox({2.4, 8.92, 0.55}, {4.4, 9.0, 1.1}, room, TextureKind::kWood, {0.1f, 0.2f, 0.32f});
  }
  b.AddBoxWithFront({4.45, 8.5, 0.0}, {4.85, 8.95, 0.55}, {0, -1}, room, TextureKind::kWood,
                    {0.1f, 0.2f, 0.32f}, TextureKind::kCabinet, {0.1f, 0.2f, 0.32f});
  b.AddObjectsOnSurface(4.47, 4.54, 8.52, 8.93, 0.55, 1, {0, -1}, room);
  const int lamp = AddLamp(s, "bedside lamp", {4.65, 8.72, 0.75}, room, 45.0 * options.lamps.intensity_scale, "");
  b.AddBox({4.62, 8.69, 0.55}, {4.68, 8.75, 0.62}, room, TextureKind::kPaint, {0.1f, 0.1f, 0.1f});
  AddShade(b, lamp, {0.1, 0.1, 0.12});
  if (options.lamps.bedroom_ceiling_cd > 0.0) {
    AddCeilingLight(b, "bedroom ceiling", {2.6, 7.0}, room, options.lamps.bedroom_ceiling_cd, options);
  }
  // Wardrobe, dresser with objects, bookshelf, rug, plant, laundry basket.
  if (options.box_furniture) {
    b.AddBoxWithFront({4.9, 6.2, 0.0}, {5.5, 8.2, 2.1}, {-1, 0}, room, TextureKind::kWood,
                      {0.2f, 0.3f, 0.4f}, TextureKind::kCabinet, {0.22f, 0.32f, 0.42f});
    b.AddBoxWithFront({0.3, 6.0, 0.0}, {1.6, 6.45, 0.8}, {0, 1}, room, TextureKind::kWood,
                      {0.15f, 0.25f, 0.35f}, TextureKind::kCabinet, {0.15f, 0.25f, 0.35f});
    b.AddObjectsOnSurface(0.35, 1.55, 6.05, 6.4, 0.8, 4, {0, 1}, room);
  }
  b.AddBox({0.0, 8.3, 0.0}, {0.35, 8.95, 1.8}, room, TextureKind::kBooks, {});
  b.AddBox({1.4, 7.2, 0.0}, {2.3, 8.6, 0.006}, room, TextureKind::kRug, {0.35f, 0.2f, 0.2f});
  if (options.box_furniture) {  // on the wardrobe's doors
    b.AddWallItem(false, 4.9, {-1, 0}, 6.65, 0.4, 1.2, 1.75, room, TextureKind::kPoster);
    b.AddBox({4.82, 7.1, 0.9}, {4.9, 7.45, 1.4}, room, TextureKind::kCurtain, {0.25f, 0.3f, 0.5f});
  }
  b.AddPlant({5.2, 8.65}, 1.3, room);
  // Window with curtains and a radiator; pictures; a switch by the door.
  b.AddCurtains(false, 0.0, {1, 0}, window, 0.8, room, 0.2);
  b.AddRadiator(false, 0.0, {1, 0}, 7.5, 1.0, room);
  b.AddVertical({3.4, 8.99}, {0, -1}, 1.0, 1.2, 1.8, room, TextureKind::kPicture, {});
  b.AddVertical({4.2, 6.01}, {0, 1}, 0.6, 1.1, 1.9, room, TextureKind::kPoster, {});
  b.AddVertical({0.95, 6.01}, {0, 1}, 0.8, 1.2, 1.8, room, TextureKind::kPicture, {});
  b.AddVertical({1.3, 8.99}, {0, -1}, 0.7, 1.1, 1.9, room, TextureKind::kPoster, {});
  b.AddSwitch(true, 6.0, {0, 1}, 1.85, 1.05, room);
}

}  // namespace

void LampOptions::Check() const {
  SLAM_THROW_IF_NOT(ConfigError, intensity_scale > 0.0)
      << "scene.lamps.intensity_scale must be > 0, got " << intensity_scale;
  SLAM_THROW_IF_NOT(ConfigError, bedroom_ceiling_cd >= 0.0 && living_ceiling_cd >= 0.0)
      << "scene.lamps.bedroom_ceiling_cd and scene.lamps.living_ceiling_cd must be >= 0";
  const bool time_ok = living_lamp_on_from.size() == 5 && living_lamp_on_from[2] == ':';
  SLAM_THROW_IF_NOT(ConfigError, time_ok)
      << "scene.lamps.living_lamp_on_from must be \"HH:MM\", got \"" << living_lamp_on_from << "\"";
  SLAM_THROW_IF_NOT(ConfigError, light.color_temperature_k >= 1000 && light.color_temperature_k <= 12000)
      << "scene.lamps.color_temperature_k must be in [1000, 12000], got " << light.color_temperature_k;
  SLAM_THROW_IF_NOT(ConfigError, light.shade_nits_per_cd >= 0.0) << "scene.lamps.shade_nits_per_cd must be >= 0";
}

void ApartmentOptions::Check() const {
  SLAM_THROW_IF_NOT(ConfigError, wall_height_m >= 2.2 && wall_height_m <= 4.0)
      << "scene.wall_height_m must be in [2.2, 4], got " << wall_height_m;
  lamps.Check();
  SLAM_THROW_IF_NOT(ConfigError, window_reflectance >= 0.0 && window_reflectance <= 0.5)
      << "scene.window_reflectance must be in [0, 0.5], got " << window_reflectance;
  SLAM_THROW_IF_NOT(ConfigError, floor_reflectance >= 0.0 && floor_reflectance <= 0.5)
      << "scene.floor_reflectance must be in [0, 0.5], got " << floor_reflectance;
  SLAM_THROW_IF_NOT(ConfigError, relief_scale >= 0.0 && relief_scale <= 10.0)
      << "scene.relief_scale must be in [0, 10], got " << relief_scale;
  furniture.Check();
  CheckPhotoMaterialSpecs(photo_materials);
}

Scene BuildApartment(const ApartmentOptions& options) {
  options.Check();
  SceneBuilder builder(options.seed,
                      options.textures_dir.empty() ? std::vector<cv::Mat>()
                                                   : LoadUserTextures(options.textures_dir),
                      options.wall_height_m, options.relief_scale);
  LoadedPhotoMaterials photos = LoadPhotoMaterials(options.photo_materials, options.furniture.catalog);
  builder.SetPhotoMaterials(std::move(photos.materials));
  Scene& s = builder.scene();
  s.material_credits = std::move(photos.credits);
  s.lamp_light = options.lamps.light;
  for (const RoomFloor& floor : ApartmentRoomFloors()) s.room_names.push_back(floor.name);
  AddLivingRoom(builder, options);
  AddKitchen(builder, options);
  AddCorridor(builder, options);
  AddBedroom(builder, options);
  for (Quad& q : s.quads) {
    if (q.emission == Emission::kSky) q.mirror_reflectance = options.window_reflectance;
    // The floors: the quads at z = 0 facing up (rugs and boxes lie above).
    if (q.normal().z() > 0.99 && std::abs(q.origin_in_world.z()) < 1e-9) {
      q.mirror_reflectance = options.floor_reflectance;
    }
  }
  s.min_corner_xy = Eigen::Vector2d(0.0, 0.0);
  s.max_corner_xy = Eigen::Vector2d(10.0, 9.0);
  s.docking_world_from_camera =
      Rigid3d(CameraRotationFromYawPitchRoll(kPi / 2, 5.0 * kPi / 180, 0.0), Eigen::Vector3d(1.7, 2.4, 1.3));
  s.window_world_from_camera =
      Rigid3d(CameraRotationFromYawPitchRoll(kPi, 0.0, 0.0), Eigen::Vector3d(3.2, 2.2, 1.3));
  AddFurniture(options.furniture, &s);
  return Scene(std::move(s));
}

std::vector<RoomFloor> ApartmentRoomFloors() {
  return {{"living room", {0.0, 0.0}, {6.0, 4.6}},
          {"kitchen", {6.1, 0.0}, {10.0, 4.6}},
          {"corridor", {0.0, 4.7}, {10.0, 5.9}},
          {"bedroom", {0.0, 6.0}, {5.5, 9.0}}};
}

std::vector<RouteWaypoint> ApartmentPatrolRoute() {
  auto wp = [](double x, double y, double spin = 0.0, double hold = 0.0,
               double face = std::numeric_limits<double>::quiet_NaN()) {
    RouteWaypoint w;
    w.position_xy = Eigen::Vector2d(x, y);
    w.spin_deg = spin;
    w.hold_s = hold;
    w.face_yaw_deg = face;
    return w;
  };
  return {wp(1.7, 2.4, 0, 3, 90),  wp(3.2, 1.8, 360), wp(5.3, 1.6),     wp(7.0, 1.0),
          wp(8.9, 1.0),            wp(8.9, 3.3, -270), wp(7.45, 3.4),   wp(7.45, 5.3),
          wp(9.0, 5.25, 0, 1, 0),   wp(2.45, 5.3),     wp(2.45, 6.6),    wp(1.0, 6.8),
          wp(1.0, 8.2, 360),       wp(1.9, 6.6),      wp(4.25, 6.55, 180), wp(2.45, 6.5),
          wp(2.45, 5.3),           wp(5.15, 5.3),     wp(5.15, 3.8),    wp(3.3, 3.9),
          wp(3.3, 2.0),            wp(1.7, 2.0),      wp(1.7, 2.4, 0, 3, 90)};
}

}  // namespace duskmap
