#include "slam/synthetic/light/lighting.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include "slam/core/check.h"
#include "slam/synthetic/light/quad_bvh.h"
#include "slam/synthetic/light/sun_texels.h"

namespace duskmap {
namespace {

constexpr double kPi = 3.14159265358979323846;
// A window texel darker than this (albedo luminance) is frame or mullion:
// opaque to the sun, not glass.
constexpr float kMullionLuminance = 0.05f;

double SkyLux(const LightingOptions& options, double elevation_deg) {
  const auto& k = options.sky_log10_lux_knots;
  if (elevation_deg < k.front()[0]) return 0.0;
  if (elevation_deg >= k.back()[0]) return std::pow(10.0, k.back()[1]);
  for (size_t i = 1; i < k.size(); ++i) {
    if (elevation_deg < k[i][0]) {
      const double s = (elevation_deg - k[i - 1][0]) / (k[i][0] - k[i - 1][0]);
      return std::pow(10.0, k[i - 1][1] + s * (k[i][1] - k[i - 1][1]));
    }
  }
  return std::pow(10.0, k.back()[1]);
}

// Sky colour: neutral-blue by day, warmer near sunset, deep blue in twilight.
cv::Vec3f SkyColor(double elevation_deg) {
  const cv::Vec3f day(1.15f, 1.0f, 0.88f), sunset(0.95f, 1.0f, 1.08f), twilight(1.6f, 1.0f, 0.62f);
  if (elevation_deg >= 8.0) return day;
  if (elevation_deg >= 0.0) {
    const float s = static_cast<float>(elevation_deg / 8.0);
    return day * s + sunset * (1.0f - s);
  }
  const float s = static_cast<float>(std::min(1.0, -elevation_deg / 5.0));
  return twilight * s + sunset * (1.0f - s);
}

bool IsLampOn(const Lamp& lamp, double clock_time_h) {
  if (lamp.on_from.empty()) return true;
  return clock_time_h >= ParseClockTime(lamp.on_from, "lamp '" + lamp.name + "'.on_from");
}

// Irradiance vector of a polygon of unit radiance seen from `point`, after
// clipping it to the upper hemisphere of the unit `normal` (Lambert's formula:
// half the sum over the edges of the edge angle times the unit normal of the
// plane through the edge and the point). Its dot product with `normal` is the
// projected solid angle; with a slightly tilted normal, the irradiance there.
Eigen::Vector3d PolygonIrradianceVector(const std::array<Eigen::Vector3d, 4>& corners,
                                        const Eigen::Vector3d& point, const Eigen::Vector3d& normal) {
  Eigen::Vector3d clipped[8];
  int count = 0;
  for (int i = 0; i < 4; ++i) {
    const Eigen::Vector3d a = corners[i] - point, b = corners[(i + 1) % 4] - point;
    const double da = normal.dot(a), db = normal.dot(b);
    if (da >= 0.0) clipped[count++] = a;
    if ((da >= 0.0) != (db >= 0.0)) clipped[count++] = a + (b - a) * (da / (da - db));
  }
  if (count < 3) return Eigen::Vector3d::Zero();
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (int i = 0; i < count; ++i) {
    const Eigen::Vector3d a = clipped[i].normalized(), b = clipped[(i + 1) % count].normalized();
    const Eigen::Vector3d cross = a.cross(b);
    const double cross_norm = cross.norm();
    if (cross_norm < 1e-12) continue;
    sum += std::atan2(cross_norm, a.dot(b)) * (cross / cross_norm);
  }
  // The winding decides the sign; the light arrives from the receiver's side.
  return 0.5 * (normal.dot(sum) >= 0.0 ? sum : -sum);
}

std::array<Eigen::Vector3d, 4> Corners(const Quad& q) {
  return {q.origin_in_world, q.PointAt(q.size_u_m, 0.0), q.PointAt(q.size_u_m, q.size_v_m),
          q.PointAt(0.0, q.size_v_m)};
}

// What a receiver in one room can be shadowed by and lit through: the room's
// opaque quads (light reaches a room only through its own windows, or from
// its own lamps; walls, furniture and fittings are assigned to the room they
// stand in; glowing lamp shades do not occlude their light), in a BVH, and
// its windows in scene order (the order their light is summed in).
struct RoomShadowing {
  int index = -1;  // into Scene::room_names (any value: an unknown room has no occluders)
  QuadBvh occluders;
  std::vector<int> windows;
};

RoomShadowing ShadowingOfRoom(const Scene& scene, int room) {
  const bool known_room = room >= 0 && room < static_cast<int>(scene.room_names.size());
  std::vector<int> opaque;
  RoomShadowing shadowing;
  shadowing.index = room;
  for (size_t i = 0; i < scene.quads.size(); ++i) {
    const Quad& q = scene.quads[i];
    if (q.room != room) continue;
    if (q.emission == Emission::kSky) shadowing.windows.push_back(static_cast<int>(i));
    if (q.emission == Emission::kNone && known_room) opaque.push_back(static_cast<int>(i));
  }
  shadowing.occluders = QuadBvh(scene.quads, opaque);
  return shadowing;
}

// Whether an occluder (one of the room's quads or a furniture mesh) lies on
// the segment from `point` along the unit `direction` up to `distance`.
bool Occluded(const Scene& scene, const RoomShadowing& room, const Eigen::Vector3d& point,
              const Eigen::Vector3d& direction, double distance, int receiver_quad) {
  if (room.occluders.Occluded(point, direction, distance, receiver_quad, 1e-4)) return true;
  // The furniture meshes (any room: light reaches a room only through its
  // own windows and from its own lamps, so a piece elsewhere is never
  // between).
  return scene.mesh_occluders.Occluded(point, direction, distance);
}

// Whether the sun reaches `point` through window `w` (mullions and the
// room's opaque quads checked).
bool SunThroughWindow(const Scene& scene, const RoomShadowing& room, const Quad& window,
                      const Eigen::Vector3d& point, const Eigen::Vector3d& to_sun,
                      int receiver_quad) {
  const double d_window = window.Intersect(point, to_sun);
  if (d_window < 0.0) return false;
  const Eigen::Vector3d hit = point + d_window * to_sun - window.origin_in_world;
  const int col = std::clamp(static_cast<int>(hit.dot(window.u_axis) / window.size_u_m * window.albedo.cols), 0, window.albedo.cols - 1);
  const int row = std::clamp(static_cast<int>(hit.dot(window.v_axis) / window.size_v_m * window.albedo.rows), 0, window.albedo.rows - 1);
  if (Luminance(window.albedo.at<cv::Vec3f>(row, col)) < kMullionLuminance) return false;
  return !Occluded(scene, room, point, to_sun, d_window, receiver_quad);
}

// Whether the sun reaches `point` through one of the room's windows it lies
// in front of (the per-texel and per-sample tests; DirectIrradiance runs the
// same test inside its loop over the windows' light).
bool SunReachesPoint(const Scene& scene, const RoomShadowing& room, const Eigen::Vector3d& point,
                     const Eigen::Vector3d& to_sun, int receiver_quad) {
  for (const int w : room.windows) {
    const Quad& window = scene.quads[static_cast<size_t>(w)];
    if (window.normal().dot(point - window.origin_in_world) <= 0.0) continue;  // behind the window
    if (SunThroughWindow(scene, room, window, point, to_sun, receiver_quad)) return true;
  }
  return false;
}

IrradianceParts DirectIrradiance(const Scene& scene, const SessionLighting& lighting,
                                 const RoomShadowing& room, const Eigen::Vector3d& point,
                                 const Eigen::Vector3d& normal, int receiver_quad, bool include_sun = true);

cv::Vec3f Scale(const cv::Vec3f& c, double s) { return c * static_cast<float>(s); }

// The irradiance vector of the rectangle u0..u1 x v0..v1 of window `q`
// (zero when empty).
Eigen::Vector3d WindowPartVector(const Quad& q, double u0, double u1, double v0, double v1,
                                 const Eigen::Vector3d& point, const Eigen::Vector3d& normal) {
  if (u1 <= u0 || v1 <= v0) return Eigen::Vector3d::Zero();
  return PolygonIrradianceVector({q.PointAt(u0, v0), q.PointAt(u1, v0), q.PointAt(u1, v1), q.PointAt(u0, v1)},
                                 point, normal);
}

void AddWindowLight(const cv::Vec3f& nits_bgr, const Eigen::Vector3d& vector, const Eigen::Vector3d& normal,
                    IrradianceParts& parts) {
  parts.sky += Scale(nits_bgr, normal.dot(vector));
  parts.direction_weighted += Luminance(nits_bgr) * vector;
}

// The facades' radiance seen through window `q`: shaded, or, where the sun
// is on the room's side of the window, with the sun at the cosine of their
// horizontal normal, the window's.
cv::Vec3f FacadeNits(const Quad& q, const SessionLighting& lighting) {
  Eigen::Vector3d facade_normal = q.normal();
  facade_normal.z() = 0.0;
  const double cos_facade_sun = std::max(0.0, facade_normal.normalized().dot(lighting.sun_direction_in_world));
  return lighting.shaded_facade_nits_bgr +
         Scale(lighting.sun_normal_lux_bgr, lighting.facade_reflectance * cos_facade_sun / kPi);
}

// Whether a window's view is split into sky, facades and ground (a vertical
// window with the view obstructed).
bool ViewObstructed(const Quad& q, const SessionLighting& lighting) {
  return lighting.window_view_obstructed && std::abs(q.v_axis.z()) >= 0.999;
}

// The light through window `q` at `point`: the sky through all of it, or,
// with an obstructed view (a vertical window, v upwards or downwards), the
// ground below the point's height, the facades up to their top's elevation
// and the sky above. The ground's boundary is exact (elevation 0 is the
// point's height at any distance). The facades' top is placed per quarter of
// the window's width at its elevation seen at the quarter's middle, which
// is off by a few per cent of the distance at the quarter's ends. Six
// polygons: the whole window, the ground, the sky per quarter; the facades
// are the rest.
void AddWindowView(const Quad& q, const SessionLighting& lighting, const Eigen::Vector3d& point,
                   const Eigen::Vector3d& normal, IrradianceParts& parts) {
  const Eigen::Vector3d whole = PolygonIrradianceVector(Corners(q), point, normal);
  const double v_up = q.v_axis.z();
  if (!ViewObstructed(q, lighting)) {
    AddWindowLight(lighting.sky_nits_bgr, whole, normal, parts);
    return;
  }
  // v of a height, and the v range from a height to the top (v upwards) or
  // to the bottom (v downwards).
  const auto v_at_height = [&](double z) {
    return std::clamp((z - q.origin_in_world.z()) / v_up, 0.0, q.size_v_m);
  };
  const auto above = [&](double u0, double u1, double z) {
    const double v = v_at_height(z);
    return v_up > 0.0 ? WindowPartVector(q, u0, u1, v, q.size_v_m, point, normal)
                      : WindowPartVector(q, u0, u1, 0.0, v, point, normal);
  };
  const Eigen::Vector3d ground = whole - above(0.0, q.size_u_m, point.z());
  Eigen::Vector3d sky = Eigen::Vector3d::Zero();
  const double tan_top = std::tan(lighting.facade_top_elevation_deg * kPi / 180.0);
  constexpr int kColumns = 4;
  for (int c = 0; c < kColumns; ++c) {
    const double u0 = q.size_u_m * c / kColumns, u1 = q.size_u_m * (c + 1) / kColumns;
    const Eigen::Vector3d middle = q.PointAt(0.5 * (u0 + u1), 0.0) - point;
    sky += above(u0, u1, point.z() + tan_top * std::hypot(middle.x(), middle.y()));
  }
  const cv::Vec3f facade_nits = FacadeNits(q, lighting);
  AddWindowLight(lighting.ground_nits_bgr, ground, normal, parts);
  AddWindowLight(facade_nits, whole - ground - sky, normal, parts);
  AddWindowLight(lighting.sky_nits_bgr, sky, normal, parts);
}

}  // namespace

void LightingOptions::Check() const {
  SLAM_THROW_IF_NOT(ConfigError, std::abs(site.latitude_deg) <= 90.0)
      << "lighting.latitude_deg must be in [-90, 90], got " << site.latitude_deg;
  SLAM_THROW_IF_NOT(ConfigError, std::abs(site.longitude_deg) <= 180.0)
      << "lighting.longitude_deg must be in [-180, 180], got " << site.longitude_deg;
  SLAM_THROW_IF_NOT(ConfigError, site.day_of_year >= 1 && site.day_of_year <= 366)
      << "lighting.day_of_year must be in [1, 366], got " << site.day_of_year;
  SLAM_THROW_IF_NOT(ConfigError, sun_illuminance_lux > 0.0) << "lighting.sun_illuminance_lux must be > 0";
  SLAM_THROW_IF_NOT(ConfigError, std::isfinite(horizon_elevation_deg) && horizon_elevation_deg >= -5.0 &&
                                     horizon_elevation_deg <= 45.0)
      << "lighting.horizon_elevation_deg must be in [-5, 45], got " << horizon_elevation_deg;
  SLAM_THROW_IF_NOT(ConfigError, glass_transmission > 0.0 && glass_transmission <= 1.0)
      << "lighting.glass_transmission must be in (0, 1], got " << glass_transmission;
  SLAM_THROW_IF_NOT(ConfigError, facade_reflectance >= 0.0 && facade_reflectance <= 1.0)
      << "lighting.facade_reflectance must be in [0, 1], got " << facade_reflectance;
  SLAM_THROW_IF_NOT(ConfigError, ground_reflectance >= 0.0 && ground_reflectance <= 1.0)
      << "lighting.ground_reflectance must be in [0, 1], got " << ground_reflectance;
  SLAM_THROW_IF_NOT(ConfigError, !window_view_in_camera || window_view_obstructed)
      << "lighting.window_view_in_camera needs lighting.window_view_obstructed";
  SLAM_THROW_IF_NOT(ConfigError, ambient_fraction >= 0.0 && ambient_fraction < 1.0)
      << "lighting.ambient_fraction must be in [0, 1), got " << ambient_fraction;
  SLAM_THROW_IF_NOT(ConfigError, ambient_leak >= 0.0 && ambient_leak < 1.0)
      << "lighting.ambient_leak must be in [0, 1), got " << ambient_leak;
  SLAM_THROW_IF_NOT(ConfigError, light_texel_m >= 0.01 && light_texel_m <= 0.5)
      << "lighting.light_texel_m must be in [0.01, 0.5], got " << light_texel_m;
  SLAM_THROW_IF_NOT(ConfigError, mesh_sun_sample_m >= 0.001 && mesh_sun_sample_m <= 0.1)
      << "lighting.mesh_sun_sample_m must be in [0.001, 0.1], got " << mesh_sun_sample_m;
  SLAM_THROW_IF_NOT(ConfigError, sky_log10_lux_knots.size() >= 2)
      << "lighting.sky_log10_lux_knots needs at least 2 knots";
  for (size_t i = 1; i < sky_log10_lux_knots.size(); ++i) {
    SLAM_THROW_IF_NOT(ConfigError, sky_log10_lux_knots[i][0] > sky_log10_lux_knots[i - 1][0])
        << "lighting.sky_log10_lux_knots elevations must increase (knot " << i << ")";
  }
}

cv::Vec3f WindowViewRadiance::Seen(int quad, const Eigen::Vector3d& direction_in_world) const {
  const size_t i = static_cast<size_t>(quad);
  if (!obstructed[i]) return sky_nits_bgr;
  if (direction_in_world.z() < 0.0) return ground_nits_bgr;
  const double horizontal = std::hypot(direction_in_world.x(), direction_in_world.y());
  if (direction_in_world.z() < horizontal * tan_facade_top) return facade_nits_bgr[i];
  return sky_nits_bgr;
}

double ParseClockTime(const std::string& hh_mm, const std::string& what) {
  int h = -1, m = -1;
  char tail = 0;
  const bool ok = hh_mm.size() == 5 && std::sscanf(hh_mm.c_str(), "%2d:%2d%c", &h, &m, &tail) == 2 &&
                  h >= 0 && h < 24 && m >= 0 && m < 60;
  SLAM_THROW_IF_NOT(ConfigError, ok) << what << ": clock time must be \"HH:MM\", got \"" << hh_mm << "\"";
  return h + m / 60.0;
}

cv::Vec3f ColorTemperatureToBgr(double kelvin) {
  // Planck's law sampled at representative wavelengths of the B, G, R
  // channels, normalised to unit luminance.
  const double wavelengths_nm[3] = {460.0, 545.0, 610.0};
  cv::Vec3f c;
  for (int i = 0; i < 3; ++i) {
    const double l = wavelengths_nm[i] * 1e-9;
    c[i] = static_cast<float>(1.0 / (std::pow(l, 5) * (std::exp(1.4388e-2 / (l * kelvin)) - 1.0)));
  }
  // Relative to a 6500 K white so that daylight maps near neutral.
  static const cv::Vec3f white = [] {
    const double wl[3] = {460.0, 545.0, 610.0};
    cv::Vec3f w;
    for (int i = 0; i < 3; ++i) {
      const double l = wl[i] * 1e-9;
      w[i] = static_cast<float>(1.0 / (std::pow(l, 5) * (std::exp(1.4388e-2 / (l * 6500.0)) - 1.0)));
    }
    return w;
  }();
  for (int i = 0; i < 3; ++i) c[i] /= white[i];
  return c / Luminance(c);
}

SessionLighting ComputeSessionLighting(const LightingOptions& options, const Scene& scene,
                                       double clock_time_h) {
  SessionLighting l;
  l.clock_time_h = clock_time_h;
  l.day_of_year = options.site.day_of_year;
  l.sun = ComputeSunPosition(options.site, clock_time_h);
  l.sun_direction_in_world = SunDirectionInWorld(l.sun);
  if (l.sun.elevation_deg > options.horizon_elevation_deg) {
    const double h = l.sun.elevation_deg;
    // Kasten-Young air mass.
    const double airmass = 1.0 / (std::sin(h * kPi / 180) + 0.50572 * std::pow(h + 6.07995, -1.6364));
    for (int c = 0; c < 3; ++c) {
      l.sun_normal_lux_bgr[c] = static_cast<float>(options.sun_illuminance_lux * options.glass_transmission *
                                                   std::exp(-options.optical_depth_bgr[c] * airmass));
    }
  }
  const double sky_lux = SkyLux(options, l.sun.elevation_deg);
  l.sky_nits_bgr = Scale(SkyColor(l.sun.elevation_deg), sky_lux / kPi * options.glass_transmission);
  if (options.window_view_obstructed) {
    l.window_view_obstructed = true;
    l.facade_top_elevation_deg = std::max(0.0, options.horizon_elevation_deg);
    l.facade_reflectance = options.facade_reflectance;
    // The ground: the sky's horizontal illuminance and the sun's when it
    // clears the horizon (sun_normal_lux_bgr is already through glass, as the
    // view of the ground is).
    const double sin_sun = std::max(0.0, std::sin(l.sun.elevation_deg * kPi / 180.0));
    l.ground_nits_bgr = Scale(l.sky_nits_bgr + Scale(l.sun_normal_lux_bgr, sin_sun / kPi), options.ground_reflectance);
    // A vertical facade under a uniform sky: half the sky's horizontal
    // illuminance, and half the ground's exitance.
    l.shaded_facade_nits_bgr = Scale(l.sky_nits_bgr + l.ground_nits_bgr, 0.5 * options.facade_reflectance);
  }
  l.lamp_color_bgr = ColorTemperatureToBgr(scene.lamp_light.color_temperature_k);
  for (const Lamp& lamp : scene.lamps) l.lamp_on.push_back(IsLampOn(lamp, clock_time_h));
  return l;
}

IrradianceParts ComputeDirectIrradiance(const Scene& scene, const SessionLighting& lighting,
                                        const Eigen::Vector3d& point, const Eigen::Vector3d& normal,
                                        int room, int receiver_quad) {
  return DirectIrradiance(scene, lighting, ShadowingOfRoom(scene, room), point, normal, receiver_quad);
}

namespace {

IrradianceParts DirectIrradiance(const Scene& scene, const SessionLighting& lighting,
                                 const RoomShadowing& room, const Eigen::Vector3d& point,
                                 const Eigen::Vector3d& normal, int receiver_quad, bool include_sun) {
  IrradianceParts parts;
  const Eigen::Vector3d& to_sun = lighting.sun_direction_in_world;
  const double cos_sun = normal.dot(to_sun);
  const bool sun_up = include_sun && lighting.sun_normal_lux_bgr[1] > 0.0f && cos_sun > 0.0;
  for (const int w : room.windows) {
    const Quad& q = scene.quads[static_cast<size_t>(w)];
    if (q.normal().dot(point - q.origin_in_world) <= 0.0) continue;  // behind the window
    AddWindowView(q, lighting, point, normal, parts);
    if (sun_up && Luminance(parts.sun) == 0.0f &&
        SunThroughWindow(scene, room, q, point, to_sun, receiver_quad)) {
      parts.sun = Scale(lighting.sun_normal_lux_bgr, cos_sun);
      parts.direction_weighted += Luminance(lighting.sun_normal_lux_bgr) * to_sun;
    }
  }
  for (size_t i = 0; i < scene.lamps.size(); ++i) {
    const Lamp& lamp = scene.lamps[i];
    if (!lighting.lamp_on[i] || lamp.room != room.index) continue;
    const Eigen::Vector3d to_lamp = lamp.position_in_world - point;
    const double r2 = std::max(to_lamp.squaredNorm(), 0.01);
    const double r = std::sqrt(r2);
    const double cos_lamp = normal.dot(to_lamp) / r;
    if (cos_lamp <= 0.0) continue;
    // Hard shadows from a point lamp: furniture, objects and walls between.
    if (Occluded(scene, room, point, to_lamp / r, r, receiver_quad)) continue;
    parts.lamps += Scale(lighting.lamp_color_bgr, lamp.intensity_cd * cos_lamp / r2);
    parts.direction_weighted += (lamp.intensity_cd / r2) * Luminance(lighting.lamp_color_bgr) * (to_lamp / r);
  }
  return parts;
}

struct LightMap {
  int nodes_u = 0, nodes_v = 0;
  std::vector<cv::Vec3f> lux;  // row-major, nodes_v rows
  // The direct light's irradiance vector (luminance) in the quad's frame
  // (along u, along v, along the normal): what a relief slope tilts into.
  std::vector<cv::Vec3f> vector_uvn;
};

LightMap ComputeLightMap(const Scene& scene, const SessionLighting& lighting,
                         const RoomShadowing& room, int quad_index, double texel_m, bool include_sun) {
  const Quad& q = scene.quads[quad_index];
  LightMap map;
  map.nodes_u = std::max(2, static_cast<int>(std::ceil(q.size_u_m / texel_m)) + 1);
  map.nodes_v = std::max(2, static_cast<int>(std::ceil(q.size_v_m / texel_m)) + 1);
  const size_t nodes = static_cast<size_t>(map.nodes_u) * map.nodes_v;
  map.lux.resize(nodes);
  if (!q.relief_slope.empty()) map.vector_uvn.resize(nodes);
  const Eigen::Vector3d n = q.normal();
  for (int j = 0; j < map.nodes_v; ++j) {
    for (int i = 0; i < map.nodes_u; ++i) {
      const Eigen::Vector3d p = q.PointAt(q.size_u_m * i / (map.nodes_u - 1), q.size_v_m * j / (map.nodes_v - 1)) + 1e-3 * n;
      const IrradianceParts parts = DirectIrradiance(scene, lighting, room, p, n, quad_index, include_sun);
      const size_t k = static_cast<size_t>(j) * map.nodes_u + i;
      map.lux[k] = parts.total();
      if (!map.vector_uvn.empty()) {
        const Eigen::Vector3d& d = parts.direction_weighted;
        map.vector_uvn[k] = cv::Vec3f(static_cast<float>(d.dot(q.u_axis)), static_cast<float>(d.dot(q.v_axis)),
                                      static_cast<float>(d.dot(n)));
      }
    }
  }
  return map;
}

// Bilinear lookup of a light-map channel at fractional quad coordinates.
cv::Vec3f SampleNodes(const LightMap& map, const std::vector<cv::Vec3f>& values, double fu, double fv) {
  const double x = fu * (map.nodes_u - 1), y = fv * (map.nodes_v - 1);
  const int i = std::min(static_cast<int>(x), map.nodes_u - 2), j = std::min(static_cast<int>(y), map.nodes_v - 2);
  const float a = static_cast<float>(x - i), b = static_cast<float>(y - j);
  const cv::Vec3f* row0 = &values[static_cast<size_t>(j) * map.nodes_u];
  const cv::Vec3f* row1 = row0 + map.nodes_u;
  return (row0[i] * (1 - a) + row0[i + 1] * a) * (1 - b) + (row1[i] * (1 - a) + row1[i + 1] * a) * b;
}

// How much of the direct light a texel whose relief tilts its normal by the
// slopes (dh/ds, dh/dt) receives, relative to the flat surface: the tilted
// normal n - s u - t v (normalised) against the irradiance vector, clamped
// at zero where the slope turns away from the light. 1 without light.
float ReliefFactor(const cv::Vec3f& vector_uvn, const cv::Vec2f& slope) {
  constexpr float kMinNormalComponent = 1e-6f;
  if (vector_uvn[2] <= kMinNormalComponent) return 1.0f;
  const float tilted = (vector_uvn[2] - slope[0] * vector_uvn[0] - slope[1] * vector_uvn[1]) /
                       std::sqrt(1.0f + slope[0] * slope[0] + slope[1] * slope[1]);
  return std::max(0.0f, tilted) / vector_uvn[2];
}

// Per-room ambient irradiance: a fraction of the area-weighted mean direct
// irradiance of the room plus a leak of the apartment mean.
// `sun_mean` (per quad, may be empty) adds the mean of a sun drawn per texel.
std::vector<cv::Vec3f> AmbientPerRoom(const Scene& scene, const std::vector<LightMap>& maps,
                                      const std::vector<cv::Vec3f>& sun_mean, const LightingOptions& options) {
  const size_t rooms = scene.room_names.size();
  std::vector<cv::Vec3d> sum(rooms, cv::Vec3d(0, 0, 0));
  std::vector<double> area(rooms, 0.0);
  for (size_t i = 0; i < scene.quads.size(); ++i) {
    const Quad& q = scene.quads[i];
    if (q.emission != Emission::kNone) continue;
    cv::Vec3d mean(0, 0, 0);
    for (const cv::Vec3f& e : maps[i].lux) mean += cv::Vec3d(e);
    mean /= static_cast<double>(maps[i].lux.size());
    if (!sun_mean.empty()) mean += cv::Vec3d(sun_mean[i]);
    const double a = q.size_u_m * q.size_v_m;
    sum[q.room] += mean * a;
    area[q.room] += a;
  }
  cv::Vec3d total(0, 0, 0);
  double total_area = 0.0;
  for (size_t r = 0; r < rooms; ++r) {
    total += sum[r];
    total_area += area[r];
  }
  std::vector<cv::Vec3f> ambient(rooms);
  for (size_t r = 0; r < rooms; ++r) {
    const cv::Vec3d room_mean = area[r] > 0.0 ? sum[r] / area[r] : cv::Vec3d(0, 0, 0);
    ambient[r] = cv::Vec3f(room_mean * options.ambient_fraction + total / std::max(total_area, 1e-9) * options.ambient_leak);
  }
  return ambient;
}

// The sun's part of a mesh's light (MeshSun): per vertex its unshadowed term
// and `vertex_sun_visible`, whether the vertex light includes it (as
// DirectIrradiance decided), and samples over the triangles with a lit and a
// shadowed vertex that both face the sun. A triangle whose sun-facing
// vertices agree keeps the vertices' interpolation (a terminator's fading
// towards a vertex facing away needs no samples).
MeshSun MeshSunOf(const Scene& scene, const SessionLighting& lighting, const RoomShadowing& room,
                  const SceneMesh& mesh, std::vector<uint8_t> vertex_sun_visible, double sample_m) {
  MeshSun sun;
  const size_t num_vertices = mesh.positions_in_world.size();
  SLAM_CHECK(vertex_sun_visible.size() == num_vertices);
  sun.vertex_sun.assign(num_vertices, cv::Vec3f(0, 0, 0));
  sun.vertex_sun_visible = std::move(vertex_sun_visible);
  sun.triangle_samples.assign(mesh.triangles.size(), -1);
  const Eigen::Vector3d& to_sun = lighting.sun_direction_in_world;
  if (lighting.sun_normal_lux_bgr[1] <= 0.0f || room.windows.empty()) return sun;
  const float inv_pi = static_cast<float>(1.0 / kPi);
  const auto reaches = [&](const Eigen::Vector3d& point, const Eigen::Vector3d& direction) {
    return SunReachesPoint(scene, room, point, direction, -1);
  };
  for (size_t v = 0; v < num_vertices; ++v) {
    const double cos_sun = mesh.normals_in_world[v].cast<double>().dot(to_sun);
    if (cos_sun > 0.0) sun.vertex_sun[v] = Scale(lighting.sun_normal_lux_bgr, cos_sun) * inv_pi;
  }
  // The widest grid: a triangle's longest edge over the sample spacing, for
  // edges up to 1 m (meshes are split at scene.furniture.max_edge_m).
  const int max_intervals = static_cast<int>(std::ceil(1.0 / sample_m));
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    const std::array<int, 3>& tri = mesh.triangles[t];
    bool lit = false, shadowed = false;
    Eigen::Vector3d normal_sum = Eigen::Vector3d::Zero();
    for (const int v : tri) {
      normal_sum += mesh.normals_in_world[static_cast<size_t>(v)].cast<double>();
      if (Luminance(sun.vertex_sun[static_cast<size_t>(v)]) <= 0.0f) continue;
      (sun.vertex_sun_visible[static_cast<size_t>(v)] ? lit : shadowed) = true;
    }
    if (!(lit && shadowed)) continue;
    const std::array<Eigen::Vector3d, 3> corners = {
        mesh.positions_in_world[static_cast<size_t>(tri[0])].cast<double>(),
        mesh.positions_in_world[static_cast<size_t>(tri[1])].cast<double>(),
        mesh.positions_in_world[static_cast<size_t>(tri[2])].cast<double>()};
    // Off the surface by 1 mm on the side its vertex normals face (catalog
    // models wind their faces either way).
    Eigen::Vector3d face = (corners[1] - corners[0]).cross(corners[2] - corners[0]);
    if (face.squaredNorm() == 0.0) continue;
    face.normalize();
    if (face.dot(normal_sum) < 0.0) face = -face;
    sun.triangle_samples[t] = static_cast<int>(sun.samples.size());
    sun.samples.push_back(SampleTriangleSun(corners, 1e-3 * face, to_sun, sample_m, max_intervals, reaches));
  }
  return sun;
}

// Each room's shadowing, built when a receiver first needs it.
class RoomShadowings {
 public:
  explicit RoomShadowings(const Scene& scene) : scene_(scene) {}

  const RoomShadowing& operator()(int room) {
    auto it = rooms_.find(room);
    if (it == rooms_.end()) it = rooms_.emplace(room, ShadowingOfRoom(scene_, room)).first;
    return it->second;
  }

 private:
  const Scene& scene_;
  std::map<int, RoomShadowing> rooms_;
};

// Stage 1: the light map of every quad but the windows; without the sun
// when the sun is drawn per texel (stage 2).
std::vector<LightMap> QuadLightMaps(const Scene& scene, const SessionLighting& lighting, RoomShadowings& rooms,
                                    double texel_m, bool include_sun) {
  std::vector<LightMap> maps(scene.quads.size());
  for (size_t i = 0; i < scene.quads.size(); ++i) {
    const Quad& q = scene.quads[i];
    if (q.emission == Emission::kSky) continue;
    maps[i] = ComputeLightMap(scene, lighting, rooms(q.room), static_cast<int>(i), texel_m, include_sun);
  }
  return maps;
}

// LightingOptions::sun_per_texel: the sun's visibility per texel of each quad
// it can reach (empty elsewhere), and its mean irradiance there for the
// ambient term. Both lists are empty when the sun is in the light maps.
struct QuadSunTexels {
  std::vector<cv::Mat> visibility;
  std::vector<cv::Vec3f> mean_lux;
};

// Stage 2 (with sun_per_texel).
QuadSunTexels SunPerTexel(const Scene& scene, const SessionLighting& lighting, RoomShadowings& rooms) {
  QuadSunTexels sun;
  sun.visibility.resize(scene.quads.size());
  sun.mean_lux.assign(scene.quads.size(), cv::Vec3f(0, 0, 0));
  const Eigen::Vector3d& to_sun = lighting.sun_direction_in_world;
  for (size_t i = 0; i < scene.quads.size(); ++i) {
    const Quad& q = scene.quads[i];
    const double cos_sun = q.normal().dot(to_sun);
    if (q.emission == Emission::kSky || lighting.sun_normal_lux_bgr[1] <= 0.0f || cos_sun <= 0.0) continue;
    const RoomShadowing& room = rooms(q.room);
    if (room.windows.empty()) continue;
    const Eigen::Vector3d offset = 1e-3 * q.normal();
    const int receiver = static_cast<int>(i);
    const auto reaches = [&](const Eigen::Vector3d& point, const Eigen::Vector3d& direction) {
      return SunReachesPoint(scene, room, point + offset, direction, receiver);
    };
    sun.visibility[i] = SunVisibility(q, q.albedo.size(), to_sun, reaches);
    sun.mean_lux[i] = Scale(lighting.sun_normal_lux_bgr, cos_sun * cv::mean(sun.visibility[i])[0]);
  }
  return sun;
}

// Stage 4 (with window_view_in_camera): what the camera sees through each
// window, by direction.
WindowViewRadiance WindowViewOf(const Scene& scene, const SessionLighting& lighting) {
  WindowViewRadiance view;
  view.enabled = true;
  view.tan_facade_top = std::tan(lighting.facade_top_elevation_deg * kPi / 180.0);
  view.sky_nits_bgr = lighting.sky_nits_bgr;
  view.ground_nits_bgr = lighting.ground_nits_bgr;
  view.facade_nits_bgr.resize(scene.quads.size(), cv::Vec3f(0, 0, 0));
  view.obstructed.resize(scene.quads.size(), false);
  for (size_t i = 0; i < scene.quads.size(); ++i) {
    if (scene.quads[i].emission != Emission::kSky) continue;
    view.facade_nits_bgr[i] = FacadeNits(scene.quads[i], lighting);
    view.obstructed[i] = ViewObstructed(scene.quads[i], lighting);
  }
  return view;
}

// A window's texture: the sky's radiance through it, or with `pane_mask` 1
// for glass and the albedo of its frame and mullions (the renderer multiplies
// it by what each pixel's ray sees outside).
cv::Mat WindowTexture(const Quad& q, const SessionLighting& lighting, bool pane_mask) {
  cv::Mat out(q.albedo.size(), CV_32FC3);
  for (int r = 0; r < out.rows; ++r) {
    const cv::Vec3f* a = q.albedo.ptr<cv::Vec3f>(r);
    cv::Vec3f* o = out.ptr<cv::Vec3f>(r);
    for (int c = 0; c < out.cols; ++c) {
      o[c] = pane_mask ? (Luminance(a[c]) < kMullionLuminance ? a[c] : cv::Vec3f(1, 1, 1))
                       : a[c].mul(lighting.sky_nits_bgr);
    }
  }
  return out;
}

// A lit lamp shade's glow: its albedo in the lamps' colour, times its lamp's
// candela and the shade's nits per candela.
cv::Mat GlowTexture(const Quad& q, const cv::Vec3f& lamp_color_bgr, double intensity_cd, double nits_per_cd) {
  cv::Mat out(q.albedo.size(), CV_32FC3);
  for (int r = 0; r < out.rows; ++r) {
    const cv::Vec3f* a = q.albedo.ptr<cv::Vec3f>(r);
    cv::Vec3f* o = out.ptr<cv::Vec3f>(r);
    for (int c = 0; c < out.cols; ++c) o[c] = a[c].mul(lamp_color_bgr) * static_cast<float>(intensity_cd * nits_per_cd);
  }
  return out;
}

// The sun drawn per texel on one quad: its irradiance there and its
// irradiance vector in the quad's frame, before each texel's visibility.
struct TexelSun {
  cv::Vec3f lux = cv::Vec3f(0, 0, 0);
  cv::Vec3f vector_uvn = cv::Vec3f(0, 0, 0);
};

TexelSun TexelSunOn(const Quad& q, const SessionLighting& lighting) {
  const Eigen::Vector3d& d = lighting.sun_direction_in_world;
  TexelSun sun;
  sun.lux = Scale(lighting.sun_normal_lux_bgr, q.normal().dot(d));
  const double luminance = Luminance(lighting.sun_normal_lux_bgr);
  sun.vector_uvn = cv::Vec3f(static_cast<float>(luminance * d.dot(q.u_axis)),
                             static_cast<float>(luminance * d.dot(q.v_axis)),
                             static_cast<float>(luminance * d.dot(q.normal())));
  return sun;
}

// A diffuse quad's radiance: albedo x (its light map's direct light, plus
// the sun per texel where `sun_visibility` is not empty, tilted by the
// relief, + the room's ambient) / pi.
cv::Mat LitTexture(const Quad& q, const SessionLighting& lighting, const LightMap& map,
                   const cv::Mat& sun_visibility, const cv::Vec3f& ambient) {
  cv::Mat out(q.albedo.size(), CV_32FC3);
  const float inv_pi = static_cast<float>(1.0 / kPi);
  const bool relief = !map.vector_uvn.empty();
  const bool texel_sun = !sun_visibility.empty();
  const TexelSun sun_on_quad = texel_sun ? TexelSunOn(q, lighting) : TexelSun();
  for (int r = 0; r < out.rows; ++r) {
    const cv::Vec3f* a = q.albedo.ptr<cv::Vec3f>(r);
    const cv::Vec2f* slope = relief ? q.relief_slope.ptr<cv::Vec2f>(r) : nullptr;
    const float* sun = texel_sun ? sun_visibility.ptr<float>(r) : nullptr;
    cv::Vec3f* o = out.ptr<cv::Vec3f>(r);
    const double fv = (r + 0.5) / out.rows;
    for (int c = 0; c < out.cols; ++c) {
      const double fu = (c + 0.5) / out.cols;
      cv::Vec3f direct = SampleNodes(map, map.lux, fu, fv);
      if (sun != nullptr) direct += sun_on_quad.lux * sun[c];
      if (relief) {
        cv::Vec3f vector_uvn = SampleNodes(map, map.vector_uvn, fu, fv);
        if (sun != nullptr) vector_uvn += sun_on_quad.vector_uvn * sun[c];
        direct *= ReliefFactor(vector_uvn, slope[c]);
      }
      o[c] = a[c].mul(direct + ambient) * inv_pi;
    }
  }
  return out;
}

// Stage 5: every quad's radiance texture.
std::vector<cv::Mat> QuadTextures(const Scene& scene, const SessionLighting& lighting, const LightingOptions& options,
                                  const std::vector<LightMap>& maps, const QuadSunTexels& sun,
                                  const std::vector<cv::Vec3f>& ambient, bool pane_mask) {
  std::vector<cv::Mat> radiance(scene.quads.size());
  for (size_t i = 0; i < scene.quads.size(); ++i) {
    const Quad& q = scene.quads[i];
    if (q.emission == Emission::kSky) {
      radiance[i] = WindowTexture(q, lighting, pane_mask);
    } else if (q.emission == Emission::kLamp && lighting.lamp_on[q.lamp]) {
      radiance[i] = GlowTexture(q, lighting.lamp_color_bgr, scene.lamps[q.lamp].intensity_cd,
                                scene.lamp_light.shade_nits_per_cd);
    } else {
      const cv::Mat no_sun;
      radiance[i] = LitTexture(q, lighting, maps[i], sun.visibility.empty() ? no_sun : sun.visibility[i],
                               ambient[q.room]);
    }
  }
  return radiance;
}

// A mesh's light per vertex: (the direct light 1 mm off its surface along
// its normal, so that its own triangles do not shadow it, + the room's
// ambient) / pi; with `sun_visible`, whether each vertex's light includes
// the sun.
std::vector<cv::Vec3f> MeshVertexLight(const Scene& scene, const SessionLighting& lighting, const RoomShadowing& room,
                                       const SceneMesh& mesh, const cv::Vec3f& room_ambient,
                                       std::vector<uint8_t>* sun_visible) {
  const float inv_pi = static_cast<float>(1.0 / kPi);
  std::vector<cv::Vec3f> light(mesh.positions_in_world.size());
  if (sun_visible != nullptr) sun_visible->assign(light.size(), 0);
  for (size_t v = 0; v < light.size(); ++v) {
    const Eigen::Vector3d n = mesh.normals_in_world[v].cast<double>();
    const Eigen::Vector3d p = mesh.positions_in_world[v].cast<double>() + 1e-3 * n;
    const IrradianceParts parts = DirectIrradiance(scene, lighting, room, p, n, -1);
    light[v] = (parts.total() + room_ambient) * inv_pi;
    if (sun_visible != nullptr) (*sun_visible)[v] = Luminance(parts.sun) > 0.0f ? 1 : 0;
  }
  return light;
}

// Stage 6: the meshes' vertex light, and with mesh_sun_per_sample the sun
// per pixel over the triangles a patch's edge crosses.
void LightMeshes(const Scene& scene, const SessionLighting& lighting, const LightingOptions& options,
                 RoomShadowings& rooms, const std::vector<cv::Vec3f>& ambient, SessionRadiance* session) {
  session->mesh_vertex_light.resize(scene.meshes.size());
  if (options.mesh_sun_per_sample) session->mesh_sun.resize(scene.meshes.size());
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    const SceneMesh& mesh = scene.meshes[m];
    const RoomShadowing& room = rooms(mesh.room);
    const bool known_room = mesh.room >= 0 && mesh.room < static_cast<int>(scene.room_names.size());
    const cv::Vec3f room_ambient = known_room ? ambient[static_cast<size_t>(mesh.room)] : cv::Vec3f(0, 0, 0);
    std::vector<uint8_t> sun_visible;
    session->mesh_vertex_light[m] = MeshVertexLight(scene, lighting, room, mesh, room_ambient,
                                                    options.mesh_sun_per_sample ? &sun_visible : nullptr);
    if (options.mesh_sun_per_sample) {
      session->mesh_sun[m] = MeshSunOf(scene, lighting, room, mesh, std::move(sun_visible), options.mesh_sun_sample_m);
    }
  }
}

}  // namespace

// The stages in order; each model choice (LightingOptions::sun_per_texel,
// window_view_in_camera, mesh_sun_per_sample) is decided here, once.
SessionRadiance PrepareSessionRadiance(const Scene& scene, const SessionLighting& lighting,
                                       const LightingOptions& options) {
  RoomShadowings rooms(scene);
  const std::vector<LightMap> maps =
      QuadLightMaps(scene, lighting, rooms, options.light_texel_m, /*include_sun=*/!options.sun_per_texel);
  const QuadSunTexels sun = options.sun_per_texel ? SunPerTexel(scene, lighting, rooms) : QuadSunTexels();
  const std::vector<cv::Vec3f> ambient = AmbientPerRoom(scene, maps, sun.mean_lux, options);  // stage 3
  SessionRadiance session;
  const bool pane_mask = options.window_view_in_camera && lighting.window_view_obstructed;
  if (pane_mask) session.window_view = WindowViewOf(scene, lighting);
  session.quads = QuadTextures(scene, lighting, options, maps, sun, ambient, pane_mask);
  LightMeshes(scene, lighting, options, rooms, ambient, &session);
  return session;
}

std::vector<cv::Mat> PrepareRadiance(const Scene& scene, const SessionLighting& lighting,
                                     const LightingOptions& options) {
  SLAM_CHECK_MSG(scene.meshes.empty(), "PrepareRadiance: a scene with meshes needs PrepareSessionRadiance");
  SLAM_CHECK_MSG(!options.window_view_in_camera,
                 "PrepareRadiance: lighting.window_view_in_camera needs PrepareSessionRadiance");
  return PrepareSessionRadiance(scene, lighting, options).quads;
}

}  // namespace duskmap
