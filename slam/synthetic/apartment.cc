#include "slam/synthetic/apartment.h"

#include <cmath>

#include "slam/core/check.h"
#include "slam/core/random.h"
#include "slam/synthetic/textures.h"

namespace duskmap {
namespace {

constexpr double kPi = 3.14159265358979323846;

struct Opening {
  double lo = 0.0, hi = 0.0;  // world coordinate along the wall (x or y)
  double z_bottom = 0.0, z_top = 0.0;
  bool window = false;
  bool reveal = false;  // add jambs, head and sill/threshold (once per opening)
  double depth_m = 0.1;  // reveal depth (wall thickness)
};

struct RoomRect {
  double x0, x1, y0, y1;
};

class ApartmentBuilder {
 public:
  explicit ApartmentBuilder(const ApartmentOptions& options) : options_(options) {
    if (!options.textures_dir.empty()) user_images_ = LoadUserTextures(options.textures_dir);
  }

  Scene& scene() { return scene_; }

  int AddQuad(const Eigen::Vector3d& origin, const Eigen::Vector3d& u, const Eigen::Vector3d& v,
              double su, double sv, int room, TextureKind kind, const cv::Vec3f& color,
              Emission emission = Emission::kNone, int lamp = -1) {
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
    request.seed = DeriveSeed(options_.seed, scene_.quads.size());
    q.albedo = MakeTexture(request, user_images_);
    scene_.quads.push_back(std::move(q));
    return static_cast<int>(scene_.quads.size()) - 1;
  }

  // Vertical rectangle whose plane passes through center_xy with horizontal
  // normal n (the visible side), spanning `width` along the plane.
  int AddVertical(const Eigen::Vector2d& center_xy, const Eigen::Vector2d& n, double width,
                  double z_bottom, double z_top, int room, TextureKind kind, const cv::Vec3f& color,
                  Emission emission = Emission::kNone, int lamp = -1) {
    const Eigen::Vector3d normal(n.x(), n.y(), 0.0);
    const Eigen::Vector3d v(0, 0, -1);
    const Eigen::Vector3d u = v.cross(normal);
    const Eigen::Vector3d origin = Eigen::Vector3d(center_xy.x(), center_xy.y(), z_top) - u * (width / 2);
    return AddQuad(origin, u, v, width, z_top - z_bottom, room, kind, color, emission, lamp);
  }

  int AddHorizontal(double x0, double x1, double y0, double y1, double z, bool up, int room,
                    TextureKind kind, const cv::Vec3f& color, Emission emission = Emission::kNone,
                    int lamp = -1) {
    if (up) return AddQuad({x0, y0, z}, {1, 0, 0}, {0, 1, 0}, x1 - x0, y1 - y0, room, kind, color, emission, lamp);
    return AddQuad({x0, y1, z}, {1, 0, 0}, {0, -1, 0}, x1 - x0, y1 - y0, room, kind, color, emission, lamp);
  }

  void AddBox(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, int room, TextureKind kind,
              const cv::Vec3f& color, Emission emission = Emission::kNone, int lamp = -1) {
    const Eigen::Vector2d c = 0.5 * (lo + hi).head<2>();
    AddHorizontal(lo.x(), hi.x(), lo.y(), hi.y(), hi.z(), true, room, kind, color, emission, lamp);
    if (emission != Emission::kNone) AddHorizontal(lo.x(), hi.x(), lo.y(), hi.y(), lo.z(), false, room, kind, color, emission, lamp);
    AddVertical({c.x(), lo.y()}, {0, -1}, hi.x() - lo.x(), lo.z(), hi.z(), room, kind, color, emission, lamp);
    AddVertical({c.x(), hi.y()}, {0, 1}, hi.x() - lo.x(), lo.z(), hi.z(), room, kind, color, emission, lamp);
    AddVertical({lo.x(), c.y()}, {-1, 0}, hi.y() - lo.y(), lo.z(), hi.z(), room, kind, color, emission, lamp);
    AddVertical({hi.x(), c.y()}, {1, 0}, hi.y() - lo.y(), lo.z(), hi.z(), room, kind, color, emission, lamp);
  }

  void AddTable(double x0, double x1, double y0, double y1, double height, int room, const cv::Vec3f& color) {
    AddBox({x0, y0, height - 0.04}, {x1, y1, height}, room, TextureKind::kWood, color);
    const double l = 0.05;
    for (const auto& [x, y] : {std::pair{x0, y0}, {x1 - l, y0}, {x0, y1 - l}, {x1 - l, y1 - l}}) {
      AddBox({x + 0.03, y + 0.03, 0.0}, {x + l, y + l, height - 0.04}, room, TextureKind::kWood, color * 0.7f);
    }
  }

  // One wall of a room. `axis_x`: the wall runs along x (south/north walls)
  // at y = plane, else along y at x = plane; n is the normal into the room.
  void AddWall(bool axis_x, double plane, double lo, double hi, const Eigen::Vector2d& n, int room,
               std::vector<Opening> openings, TextureKind kind, const cv::Vec3f& color) {
    const double h = options_.wall_height_m;
    std::sort(openings.begin(), openings.end(), [](const Opening& a, const Opening& b) { return a.lo < b.lo; });
    auto at = [&](double along) {
      return axis_x ? Eigen::Vector2d(along, plane) : Eigen::Vector2d(plane, along);
    };
    auto piece = [&](double a, double b, double zb, double zt) {
      if (b - a > 1e-3 && zt - zb > 1e-3) AddVertical(at(0.5 * (a + b)), n, b - a, zb, zt, room, kind, color);
    };
    double cursor = lo;
    for (const Opening& o : openings) {
      piece(cursor, o.lo, 0.0, h);
      piece(o.lo, o.hi, 0.0, o.z_bottom);
      piece(o.lo, o.hi, o.z_top, h);
      cursor = o.hi;
      if (o.window) AddWindow(axis_x, plane, n, o, room);
      if (o.reveal) AddReveal(axis_x, plane, n, o, room);
    }
    piece(cursor, hi, 0.0, h);
  }

  void AddRoomShell(const RoomRect& r, int room, const std::vector<std::vector<Opening>>& openings_swne,
                    TextureKind wall_kind, const cv::Vec3f& wall_color, TextureKind floor_kind,
                    const cv::Vec3f& floor_color) {
    AddWall(true, r.y0, r.x0, r.x1, {0, 1}, room, openings_swne[0], wall_kind, wall_color);
    AddWall(false, r.x0, r.y0, r.y1, {1, 0}, room, openings_swne[1], wall_kind, wall_color);
    AddWall(true, r.y1, r.x0, r.x1, {0, -1}, room, openings_swne[2], wall_kind, wall_color);
    AddWall(false, r.x1, r.y0, r.y1, {-1, 0}, room, openings_swne[3], wall_kind, wall_color);
    AddHorizontal(r.x0, r.x1, r.y0, r.y1, 0.0, true, room, floor_kind, floor_color);
    AddHorizontal(r.x0, r.x1, r.y0, r.y1, options_.wall_height_m, false, room, TextureKind::kCeiling,
                  {0.85f, 0.86f, 0.86f});
  }

 private:
  void AddWindow(bool axis_x, double plane, const Eigen::Vector2d& n, const Opening& o, int room) {
    const Eigen::Vector2d center = (axis_x ? Eigen::Vector2d(0.5 * (o.lo + o.hi), plane)
                                           : Eigen::Vector2d(plane, 0.5 * (o.lo + o.hi))) -
                                   n * o.depth_m;
    AddVertical(center, n, o.hi - o.lo, o.z_bottom, o.z_top, room, TextureKind::kWindow,
                {1.0f, 1.0f, 1.0f}, Emission::kSky);
  }

  void AddReveal(bool axis_x, double plane, const Eigen::Vector2d& n, const Opening& o, int room) {
    const cv::Vec3f white(0.8f, 0.8f, 0.8f);
    const double outer = plane - (axis_x ? n.y() : n.x()) * o.depth_m;
    const double a = std::min(plane, outer), b = std::max(plane, outer);
    auto horizontal = [&](double z, bool up, TextureKind kind, const cv::Vec3f& color) {
      if (axis_x) AddHorizontal(o.lo, o.hi, a, b, z, up, room, kind, color);
      else AddHorizontal(a, b, o.lo, o.hi, z, up, room, kind, color);
    };
    horizontal(o.z_top, false, TextureKind::kPaint, white);
    if (o.z_bottom > 0.0) horizontal(o.z_bottom, true, TextureKind::kWood, {0.7f, 0.72f, 0.75f});
    else horizontal(0.0, true, TextureKind::kWoodFloor, {0.2f, 0.32f, 0.45f});
    const double mid = 0.5 * (a + b);
    const Eigen::Vector2d along = axis_x ? Eigen::Vector2d(1, 0) : Eigen::Vector2d(0, 1);
    const Eigen::Vector2d c_lo = axis_x ? Eigen::Vector2d(o.lo, mid) : Eigen::Vector2d(mid, o.lo);
    const Eigen::Vector2d c_hi = axis_x ? Eigen::Vector2d(o.hi, mid) : Eigen::Vector2d(mid, o.hi);
    AddVertical(c_lo, along, b - a, o.z_bottom, o.z_top, room, TextureKind::kPaint, white);
    AddVertical(c_hi, -along, b - a, o.z_bottom, o.z_top, room, TextureKind::kPaint, white);
  }

  ApartmentOptions options_;
  std::vector<cv::Mat> user_images_;
  Scene scene_;
};

Opening Door(double lo, double hi, bool reveal) { return {lo, hi, 0.0, 2.1, false, reveal, 0.1}; }
Opening Window(double lo, double hi, double zb, double zt) { return {lo, hi, zb, zt, true, true, 0.15}; }

int AddLamp(Scene& scene, const std::string& name, const Eigen::Vector3d& p, int room, double cd,
            const std::string& on_from) {
  scene.lamps.push_back({name, p, room, cd, on_from});
  return static_cast<int>(scene.lamps.size()) - 1;
}

void AddLivingRoom(ApartmentBuilder& b, const ApartmentOptions& options) {
  Scene& s = b.scene();
  const int room = 0;
  const cv::Vec3f paint(0.62f, 0.68f, 0.70f);  // warm off-white (BGR)
  b.AddRoomShell({0, 6, 0, 4.6}, room,
                 {{Window(2.0, 4.2, 0.4, 2.2)},
                  {Window(0.7, 1.9, 0.8, 2.2), Window(2.7, 3.9, 0.8, 2.2)},
                  {Door(4.7, 5.6, true)},
                  {Opening{1.2, 3.6, 0.0, 2.2, false, true, 0.1}}},
                 TextureKind::kPaint, paint, TextureKind::kWoodFloor, {0.22f, 0.36f, 0.52f});
  // Docking picture above the sofa, on the north wall.
  s.docking_picture = b.AddVertical({1.7, 4.59}, {0, -1}, 1.4, 1.15, 2.05, room, TextureKind::kDocking, {});
  b.AddBox({0.6, 3.75, 0.0}, {2.8, 4.6, 0.45}, room, TextureKind::kFabric, {0.35f, 0.25f, 0.2f});
  b.AddBox({0.6, 4.3, 0.45}, {2.8, 4.58, 0.85}, room, TextureKind::kFabric, {0.33f, 0.24f, 0.19f});
  b.AddBox({0.7, 2.5, 0.0}, {2.9, 3.7, 0.006}, room, TextureKind::kRug, {0.15f, 0.2f, 0.45f});
  b.AddBox({1.1, 2.95, 0.0}, {2.3, 3.5, 0.42}, room, TextureKind::kWood, {0.1f, 0.18f, 0.3f});
  b.AddBox({4.4, 0.0, 0.0}, {5.9, 0.35, 2.0}, room, TextureKind::kBooks, {});
  b.AddTable(3.9, 5.1, 2.2, 3.0, 0.76, room, {0.15f, 0.3f, 0.45f});
  b.AddBox({0.0, 2.0, 0.0}, {0.45, 2.6, 0.6}, room, TextureKind::kWood, {0.12f, 0.12f, 0.14f});
  b.AddVertical({0.01, 2.3}, {1, 0}, 0.5, 1.2, 1.8, room, TextureKind::kPoster, {});
  b.AddVertical({5.99, 4.1}, {-1, 0}, 0.7, 1.1, 2.0, room, TextureKind::kPoster, {});
  b.AddVertical({5.99, 0.6}, {-1, 0}, 0.8, 1.2, 1.8, room, TextureKind::kPicture, {});
  b.AddVertical({3.6, 4.59}, {0, -1}, 0.7, 1.2, 1.9, room, TextureKind::kPoster, {});
  b.AddVertical({1.0, 0.01}, {0, 1}, 0.6, 1.2, 1.7, room, TextureKind::kPicture, {});
  const int floor_lamp = AddLamp(s, "living floor lamp", {5.6, 4.2, 1.6}, room,
                                 120.0 * options.lamp_intensity_scale, options.living_lamp_on_from);
  b.AddBox({5.58, 4.18, 0.0}, {5.62, 4.22, 1.45}, room, TextureKind::kWood, {0.05f, 0.05f, 0.05f});
  b.AddBox({5.45, 4.05, 1.45}, {5.75, 4.35, 1.75}, room, TextureKind::kLampShade, {0.55f, 0.75f, 0.85f},
           Emission::kLamp, floor_lamp);
  const int table_lamp = AddLamp(s, "living table lamp", {0.22, 2.3, 0.85}, room,
                                 35.0 * options.lamp_intensity_scale, "");
  b.AddBox({0.12, 2.2, 0.7}, {0.32, 2.4, 0.92}, room, TextureKind::kLampShade, {0.55f, 0.75f, 0.85f},
           Emission::kLamp, table_lamp);
}

void AddKitchen(ApartmentBuilder& b, const ApartmentOptions& options) {
  Scene& s = b.scene();
  const int room = 1;
  b.AddRoomShell({6.1, 10, 0, 4.6}, room,
                 {{Window(7.3, 8.9, 1.0, 2.1)},
                  {Opening{1.2, 3.6, 0.0, 2.2, false, false, 0.1}},
                  {Door(7.0, 7.9, true)},
                  {}},
                 TextureKind::kTiles, {0.75f, 0.78f, 0.78f}, TextureKind::kTiles, {0.35f, 0.38f, 0.4f});
  b.AddBox({9.4, 0.3, 0.0}, {10.0, 4.2, 0.9}, room, TextureKind::kWood, {0.3f, 0.45f, 0.55f});
  b.AddBox({9.65, 0.3, 1.5}, {10.0, 4.2, 2.2}, room, TextureKind::kWood, {0.3f, 0.45f, 0.55f});
  b.AddBox({6.15, 3.9, 0.0}, {6.85, 4.55, 1.8}, room, TextureKind::kPaint, {0.8f, 0.8f, 0.8f});
  b.AddTable(7.3, 8.5, 1.6, 2.6, 0.76, room, {0.2f, 0.35f, 0.5f});
  b.AddVertical({8.75, 4.59}, {0, -1}, 0.9, 1.2, 1.9, room, TextureKind::kPoster, {});
  b.AddVertical({9.99, 4.45}, {-1, 0}, 0.25, 1.0, 1.4, room, TextureKind::kPicture, {});
  b.AddVertical({9.99, 1.3}, {-1, 0}, 0.5, 1.0, 1.42, room, TextureKind::kPicture, {});
  b.AddVertical({6.65, 0.01}, {0, 1}, 0.6, 1.1, 1.9, room, TextureKind::kPoster, {});
  const int lamp = AddLamp(s, "kitchen ceiling", {8.0, 2.3, 2.25}, room, 110.0 * options.lamp_intensity_scale, "");
  b.AddBox({7.85, 2.15, 2.3}, {8.15, 2.45, 2.45}, room, TextureKind::kLampShade, {0.55f, 0.75f, 0.85f},
           Emission::kLamp, lamp);
}

void AddCorridor(ApartmentBuilder& b, const ApartmentOptions& options) {
  Scene& s = b.scene();
  const int room = 2;
  b.AddRoomShell({0, 10, 4.7, 5.9}, room,
                 {{Door(4.7, 5.6, false), Door(7.0, 7.9, false)}, {}, {Door(2.0, 2.9, true)}, {}},
                 TextureKind::kPaint, {0.55f, 0.62f, 0.66f}, TextureKind::kWoodFloor, {0.2f, 0.32f, 0.45f});
  b.AddVertical({7.9, 5.89}, {0, -1}, 0.8, 0.0, 2.05, room, TextureKind::kDoor, {0.8f, 0.8f, 0.78f});
  b.AddVertical({9.99, 5.3}, {-1, 0}, 0.9, 0.0, 2.05, room, TextureKind::kDoor, {0.3f, 0.4f, 0.5f});
  b.AddVertical({4.2, 5.89}, {0, -1}, 0.6, 1.2, 1.8, room, TextureKind::kPicture, {});
  b.AddVertical({6.5, 5.89}, {0, -1}, 0.5, 1.3, 1.9, room, TextureKind::kPoster, {});
  b.AddVertical({1.2, 4.71}, {0, 1}, 0.8, 1.2, 1.8, room, TextureKind::kPicture, {});
  b.AddVertical({3.4, 4.71}, {0, 1}, 0.6, 1.1, 1.9, room, TextureKind::kPoster, {});
  b.AddVertical({9.0, 4.71}, {0, 1}, 0.6, 1.2, 1.8, room, TextureKind::kPicture, {});
  b.AddVertical({0.01, 5.3}, {1, 0}, 0.6, 1.1, 1.9, room, TextureKind::kPoster, {});
  b.AddBox({9.0, 5.5, 0.0}, {9.9, 5.9, 1.0}, room, TextureKind::kWood, {0.25f, 0.3f, 0.35f});
  for (double x : {2.5, 7.5}) {
    const int lamp = AddLamp(s, "corridor ceiling", {x, 5.3, 2.3}, room, 70.0 * options.lamp_intensity_scale, "");
    b.AddBox({x - 0.12, 5.18, 2.38}, {x + 0.12, 5.42, 2.48}, room, TextureKind::kLampShade,
             {0.55f, 0.75f, 0.85f}, Emission::kLamp, lamp);
  }
}

void AddBedroom(ApartmentBuilder& b, const ApartmentOptions& options) {
  Scene& s = b.scene();
  const int room = 3;
  b.AddRoomShell({0, 5.5, 6.0, 9.0}, room,
                 {{Door(2.0, 2.9, false)}, {Window(6.9, 8.1, 0.9, 2.1)}, {}, {}},
                 TextureKind::kPaint, {0.5f, 0.62f, 0.72f}, TextureKind::kWoodFloor, {0.25f, 0.38f, 0.5f});
  b.AddBox({2.4, 7.0, 0.0}, {4.4, 9.0, 0.55}, room, TextureKind::kFabric, {0.55f, 0.45f, 0.4f});
  b.AddBox({2.4, 8.92, 0.55}, {4.4, 9.0, 1.1}, room, TextureKind::kWood, {0.1f, 0.2f, 0.32f});
  b.AddBox({4.9, 6.2, 0.0}, {5.5, 8.2, 2.1}, room, TextureKind::kWood, {0.2f, 0.3f, 0.4f});
  b.AddBox({4.45, 8.5, 0.0}, {4.85, 8.95, 0.55}, room, TextureKind::kWood, {0.1f, 0.2f, 0.32f});
  b.AddBox({0.3, 6.0, 0.0}, {1.6, 6.45, 0.8}, room, TextureKind::kWood, {0.15f, 0.25f, 0.35f});
  b.AddBox({0.0, 8.3, 0.0}, {0.35, 8.95, 1.8}, room, TextureKind::kBooks, {});
  b.AddBox({1.4, 7.2, 0.0}, {2.3, 8.6, 0.006}, room, TextureKind::kRug, {0.35f, 0.2f, 0.2f});
  b.AddVertical({3.4, 8.99}, {0, -1}, 1.0, 1.2, 1.8, room, TextureKind::kPicture, {});
  b.AddVertical({4.2, 6.01}, {0, 1}, 0.6, 1.1, 1.9, room, TextureKind::kPoster, {});
  b.AddVertical({0.95, 6.01}, {0, 1}, 0.8, 1.2, 1.8, room, TextureKind::kPicture, {});
  b.AddVertical({1.3, 8.99}, {0, -1}, 0.7, 1.1, 1.9, room, TextureKind::kPoster, {});
  const int lamp = AddLamp(s, "bedside lamp", {4.65, 8.72, 0.75}, room, 45.0 * options.lamp_intensity_scale, "");
  b.AddBox({4.55, 8.62, 0.6}, {4.75, 8.82, 0.85}, room, TextureKind::kLampShade, {0.55f, 0.75f, 0.85f},
           Emission::kLamp, lamp);
}

}  // namespace

void ApartmentOptions::Check() const {
  SLAM_THROW_IF_NOT(ConfigError, wall_height_m >= 2.2 && wall_height_m <= 4.0)
      << "scene.wall_height_m must be in [2.2, 4], got " << wall_height_m;
  SLAM_THROW_IF_NOT(ConfigError, lamp_intensity_scale > 0.0)
      << "scene.lamp_intensity_scale must be > 0, got " << lamp_intensity_scale;
  const bool time_ok = living_lamp_on_from.size() == 5 && living_lamp_on_from[2] == ':';
  SLAM_THROW_IF_NOT(ConfigError, time_ok)
      << "scene.living_lamp_on_from must be \"HH:MM\", got \"" << living_lamp_on_from << "\"";
}

Scene BuildApartment(const ApartmentOptions& options) {
  options.Check();
  ApartmentBuilder builder(options);
  Scene& s = builder.scene();
  s.room_names = {"living room", "kitchen", "corridor", "bedroom"};
  AddLivingRoom(builder, options);
  AddKitchen(builder, options);
  AddCorridor(builder, options);
  AddBedroom(builder, options);
  s.min_corner_xy = Eigen::Vector2d(0.0, 0.0);
  s.max_corner_xy = Eigen::Vector2d(10.0, 9.0);
  s.docking_world_from_camera =
      Rigid3d(CameraRotationFromYawPitchRoll(kPi / 2, 5.0 * kPi / 180, 0.0), Eigen::Vector3d(1.7, 2.4, 1.3));
  s.window_world_from_camera =
      Rigid3d(CameraRotationFromYawPitchRoll(kPi, 0.0, 0.0), Eigen::Vector3d(3.2, 2.2, 1.3));
  return Scene(std::move(s));
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
          wp(9.3, 5.3, 0, 1, 0),   wp(2.45, 5.3),     wp(2.45, 6.6),    wp(1.0, 6.8),
          wp(1.0, 8.2, 360),       wp(1.9, 6.6),      wp(4.6, 6.5, 180), wp(2.45, 6.5),
          wp(2.45, 5.3),           wp(5.15, 5.3),     wp(5.15, 3.8),    wp(3.3, 3.9),
          wp(3.3, 2.0),            wp(1.7, 2.0),      wp(1.7, 2.4, 0, 3, 90)};
}

}  // namespace duskmap
