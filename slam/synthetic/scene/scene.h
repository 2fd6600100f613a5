// The scene of the synthetic apartment: textured planar rectangles ("quads")
// grouped by room, the lamps, and the named viewpoints the route and previews
// use. World frame: x east, y north, z up, metres; floor at z = 0.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "slam/core/rigid3.h"
#include "slam/synthetic/raster/triangle_bvh.h"
#include "slam/synthetic/scene/scene_mesh.h"

namespace duskmap {

// What lights a quad's own radiance, besides reflected light.
enum class Emission {
  kNone,  // diffuse surface, radiance = albedo * irradiance / pi
  kSky,   // window glass: shows the sky (radiance scaled by the session's sky)
  kLamp,  // lamp shade: glows when its lamp is on
};

struct Quad {
  Eigen::Vector3d origin_in_world;  // corner at texture (0, 0)
  Eigen::Vector3d u_axis;           // unit, along texture columns
  Eigen::Vector3d v_axis;           // unit, along texture rows; u x v = visible normal
  double size_u_m = 0.0;
  double size_v_m = 0.0;
  int room = 0;                     // index into Scene::room_names
  Emission emission = Emission::kNone;
  int lamp = -1;                    // for kLamp: index into Scene::lamps
  // Mirror reflectance at normal incidence (window glass: the Fresnel R0 of
  // its faces); the renderer adds the mirrored room, weighted by Schlick's
  // approximation, to what the quad shows. 0 = not a mirror.
  double mirror_reflectance = 0.0;
  cv::Mat albedo;                   // CV_32FC3 linear BGR in [0, 1], rows along v
  // Surface relief as slopes of its height per texel, (dh/ds, dh/dt) along
  // u and v (CV_32FC2, metres per metre, the albedo's size), or empty for a
  // flat surface. It tilts the shading normal to n - dh/ds u - dh/dt v, so
  // the relief shows by where the light comes from (lighting.h).
  cv::Mat relief_slope;

  Eigen::Vector3d normal() const { return u_axis.cross(v_axis); }
  Eigen::Vector3d PointAt(double s_m, double t_m) const {
    return origin_in_world + s_m * u_axis + t_m * v_axis;
  }
  // Ray intersection: distance along the unit `direction` from `from` to the
  // quad's rectangle, or a negative value when it misses.
  double Intersect(const Eigen::Vector3d& from, const Eigen::Vector3d& direction) const;
};

struct Lamp {
  std::string name;
  Eigen::Vector3d position_in_world;
  int room = 0;
  double intensity_cd = 60.0;  // luminous intensity, candela, isotropic
  std::string on_from;         // local "HH:MM" from which it is on; empty = always on
};

// How the scene's lamps shine (LampOptions, apartment.h): the colour of
// their light and the glow of a lit lamp's shade.
struct LampLight {
  double color_temperature_k = 2700;  // warm incandescent/LED
  double shade_nits_per_cd = 15.0;    // glowing shade radiance per lamp candela
};

// A third-party file the scene shows besides its meshes (a photographic
// material), as the dataset's manifest credits it.
struct AssetCredit {
  std::string name;    // "american_oak.jpg"
  std::string source;  // "BlendSwap-CC-0.sh3f#blendswap-cc-0/lowerCabinet/american_oak.jpg"
  std::string creator;
  std::string license;
};

struct Scene {
  std::vector<std::string> room_names;
  std::vector<Quad> quads;
  std::vector<Lamp> lamps;
  LampLight lamp_light;
  // Furniture meshes (scene_mesh.h), lit per vertex and drawn after the
  // quads; and their triangles for shadow rays, kept in step by
  // SetMeshes.
  std::vector<SceneMesh> meshes;
  TriangleBvh mesh_occluders;
  std::vector<AssetCredit> material_credits;  // photographic materials (photo_materials.h)
  Eigen::Vector2d min_corner_xy = Eigen::Vector2d::Zero();  // footprint, metres
  Eigen::Vector2d max_corner_xy = Eigen::Vector2d::Zero();
  int docking_picture = -1;           // quad index of the docking picture
  Rigid3d docking_world_from_camera;  // camera pose facing the docking picture
  Rigid3d window_world_from_camera;   // living room view towards a window (previews)

  double FloorAreaM2() const;
  // Replaces the meshes and rebuilds mesh_occluders.
  void SetMeshes(std::vector<SceneMesh> new_meshes);
};

// Camera orientation looking along yaw (radians from +x towards +y), with
// pitch (radians, positive up) and roll (radians, about the optical axis).
Eigen::Matrix3d CameraRotationFromYawPitchRoll(double yaw_rad, double pitch_rad, double roll_rad);

}  // namespace duskmap
