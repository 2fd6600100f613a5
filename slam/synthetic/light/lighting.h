// Illumination of the apartment as a function of the local clock time: the
// sun through the windows (with cast shadows), the sky through the windows
// (fading through civil twilight), the 2700 K lamps and an ambient term for
// interreflection. Units: illuminance in lux, radiance in nits (cd/m2); a
// diffuse surface has radiance albedo * E / pi. Colours are linear BGR.
#pragma once

#include <array>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "slam/synthetic/light/mesh_sun.h"
#include "slam/synthetic/light/solar.h"
#include "slam/synthetic/scene/scene.h"

namespace duskmap {

struct LightingOptions {
  SolarSite site;                          // location and date
  double sun_illuminance_lux = 127000.0;   // direct normal above the atmosphere
  std::array<double, 3> optical_depth_bgr = {0.30, 0.21, 0.14};  // per airmass (reddening)
  double horizon_elevation_deg = 1.5;      // buildings/trees hide the sun below this
  // Horizontal sky illuminance: log10(lux) at sun elevations (deg), linear in
  // between, zero below the first knot.
  std::vector<std::array<double, 2>> sky_log10_lux_knots = {
      {-12.0, -1.5}, {-6.0, 0.5}, {-3.0, 1.6}, {0.0, 2.6}, {5.0, 3.4}, {15.0, 3.9}, {30.0, 4.1}};
  double glass_transmission = 0.75;        // fraction through the window glass
  // What the windows' lower directions see. Off: the sky fills every
  // direction through a window. On: a direction below horizon_elevation_deg
  // sees the facades opposite, one below 0 degrees the ground, each a diffuse
  // reflector: the ground lit by the sky (and the sun when it clears the
  // horizon), the facades by half the sky and half the ground's light (they
  // face the windows, away from the afternoon sun of the south and west
  // windows; a sunlit facade adds the sun at its cosine).
  bool window_view_obstructed = false;
  // With window_view_obstructed (which it needs): the camera sees that view
  // through the glass too, by each pixel's viewing direction (the sky above
  // the facades' top, the facades below it, the ground below the horizon),
  // instead of the window texture's fixed sky and silhouettes. Renders need
  // PrepareSessionRadiance's window_view; mirrors are not supported with it.
  bool window_view_in_camera = false;
  double facade_reflectance = 0.3;  // brick, concrete (daylighting practice: 0.2-0.4)
  double ground_reflectance = 0.2;  // street, grass (the CIE's usual ground albedo)
  double ambient_fraction = 0.35;          // interreflection: fraction of the room's mean irradiance
  double ambient_leak = 0.06;              // fraction of the apartment mean reaching every room
  double light_texel_m = 0.05;             // light-map spacing
  // The sun per texel of each quad's texture (sun_texels.h: antialiased
  // edges, the penumbra of the sun's disc) instead of through the light
  // map's nodes, which draw a sun patch's slanted edges as stairs of
  // light_texel_m. Meshes keep the sun per vertex either way. Off: the
  // datasets generated before 2026-12-06, byte for byte.
  bool sun_per_texel = false;
  // The sun per pixel over a mesh's triangles whose vertices disagree about
  // it (one lit, one shadowed: a patch's edge crosses the triangle), from a
  // barycentric grid of about mesh_sun_sample_m (mesh_sun.h), instead of a
  // gradient between the vertices. Off: every mesh pixel interpolates its
  // vertices' light, as before 2026-12-06.
  bool mesh_sun_per_sample = false;
  double mesh_sun_sample_m = 0.005;

  void Check() const;
};

// The light state of one session.
struct SessionLighting {
  double clock_time_h = 0.0;
  int day_of_year = 0;  // the date of the sun's path (LightingOptions::site)
  SunPosition sun;
  Eigen::Vector3d sun_direction_in_world = Eigen::Vector3d::UnitZ();
  cv::Vec3f sun_normal_lux_bgr = cv::Vec3f(0, 0, 0);  // direct normal, after glass; 0 when hidden
  cv::Vec3f sky_nits_bgr = cv::Vec3f(0, 0, 0);        // sky radiance seen through glass
  // LightingOptions::window_view_obstructed: the radiance of the ground and
  // of the shaded facades opposite, seen through glass, and the elevation
  // of the facades' top (off: zero radiances, the sky in every direction).
  bool window_view_obstructed = false;
  double facade_top_elevation_deg = 0.0;
  double facade_reflectance = 0.0;
  cv::Vec3f ground_nits_bgr = cv::Vec3f(0, 0, 0);
  cv::Vec3f shaded_facade_nits_bgr = cv::Vec3f(0, 0, 0);
  std::vector<bool> lamp_on;                          // per Scene::lamps
  cv::Vec3f lamp_color_bgr = cv::Vec3f(1, 1, 1);      // unit-luminance lamp colour
};

// "HH:MM" -> hours; throws ConfigError naming `what` when malformed.
double ParseClockTime(const std::string& hh_mm, const std::string& what);

SessionLighting ComputeSessionLighting(const LightingOptions& options, const Scene& scene,
                                       double clock_time_h);

// Linear-BGR colour of a black body at this temperature, unit luminance.
cv::Vec3f ColorTemperatureToBgr(double kelvin);

// Direct irradiance at a point by source (no ambient term).
struct IrradianceParts {
  cv::Vec3f sun = cv::Vec3f(0, 0, 0);
  cv::Vec3f sky = cv::Vec3f(0, 0, 0);
  cv::Vec3f lamps = cv::Vec3f(0, 0, 0);
  // Irradiance vector of all three in luminance (lux): the sum over the
  // sources of their luminance times the unit direction the light arrives
  // from (for a window, the sky's radiance times its polygon's vector). Its
  // component along the normal is Luminance(total()); tilting the normal
  // (a relief slope) weighs the light by where it comes from.
  Eigen::Vector3d direction_weighted = Eigen::Vector3d::Zero();
  cv::Vec3f total() const { return sun + sky + lamps; }
};
IrradianceParts ComputeDirectIrradiance(const Scene& scene, const SessionLighting& lighting,
                                        const Eigen::Vector3d& point, const Eigen::Vector3d& normal,
                                        int room, int receiver_quad);

// What the camera sees through the windows when
// LightingOptions::window_view_in_camera is on: the radiance a viewing ray
// finds outside, by its elevation (the facades and the ground at a distance
// where the camera's own displacement does not matter).
struct WindowViewRadiance {
  bool enabled = false;
  double tan_facade_top = 0.0;  // tangent of the facades' top elevation
  cv::Vec3f sky_nits_bgr = cv::Vec3f(0, 0, 0);
  cv::Vec3f ground_nits_bgr = cv::Vec3f(0, 0, 0);
  // Per scene quad: the facades' radiance seen through that window (a sunlit
  // facade depends on the window's side); meaningful for obstructed windows.
  std::vector<cv::Vec3f> facade_nits_bgr;
  // Per scene quad: whether its view is split (a vertical window); other
  // windows show the sky in every direction, as their light does.
  std::vector<bool> obstructed;

  // The radiance seen along `direction_in_world` through window quad `quad`.
  cv::Vec3f Seen(int quad, const Eigen::Vector3d& direction_in_world) const;
};

// What a session's frames are rendered with (renderer.h).
struct SessionRadiance {
  // The radiance texture (nits, CV_32FC3) of every quad: albedo x light map
  // / pi for diffuse quads (light map with ambient term), the sky for
  // windows, the glow of lit lamp shades. With window_view.enabled a
  // window's texture is a pane mask instead (1 for glass, the albedo of its
  // frame and mullions), which the renderer multiplies by what a pixel's
  // viewing ray sees outside.
  std::vector<cv::Mat> quads;
  WindowViewRadiance window_view;
  // Per scene mesh, per vertex: (direct irradiance + the room's ambient) /
  // pi, the radiance of a unit albedo there (nits, linear BGR); the renderer
  // interpolates it over each triangle and multiplies the texture's albedo.
  std::vector<std::vector<cv::Vec3f>> mesh_vertex_light;
  // LightingOptions::mesh_sun_per_sample (empty when off): per scene mesh,
  // the sun's part of its vertices' light and its samples over the triangles
  // whose vertices disagree about it.
  std::vector<MeshSun> mesh_sun;
};

// Lighting preparation of a session: quads and meshes, in stages: (1) the
// quads' light maps (direct light at nodes every light_texel_m, the sun
// included unless sun_per_texel), (2) with sun_per_texel the sun's
// visibility per texel, (3) each room's ambient term, (4) with
// window_view_in_camera the windows' view, (5) the quads' radiance textures,
// (6) the meshes' vertex light (with mesh_sun_per_sample, the sun per pixel
// where a patch's edge crosses a triangle). Meshes cast shadows on quads and
// on each other; they are left out of the ambient term (the room's mean over
// its quads).
SessionRadiance PrepareSessionRadiance(const Scene& scene, const SessionLighting& lighting,
                                       const LightingOptions& options);

// The quads' radiance textures alone, for a scene without meshes.
std::vector<cv::Mat> PrepareRadiance(const Scene& scene, const SessionLighting& lighting,
                                     const LightingOptions& options);

// Luminance of a linear BGR colour (Rec. 709 weights).
inline float Luminance(const cv::Vec3f& bgr) {
  return 0.0722f * bgr[0] + 0.7152f * bgr[1] + 0.2126f * bgr[2];
}

}  // namespace duskmap
