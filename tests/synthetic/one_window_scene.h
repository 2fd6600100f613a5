// The lighting tests' room: one window 2 m wide from 0.9 to 2.1 m in the
// plane x = 0, showing the sky, the room at x > 0; and a low sun alone.
#pragma once

#include <opencv2/core.hpp>

#include "slam/synthetic/light/lighting.h"
#include "slam/synthetic/scene/scene.h"

namespace duskmap {

inline Scene OneWindowScene() {
  Scene scene;
  scene.room_names = {"test room"};
  Quad window;
  window.origin_in_world = Eigen::Vector3d(0.0, -1.0, 0.9);
  window.u_axis = Eigen::Vector3d::UnitY();  // normal u x v = +x, into the room
  window.v_axis = Eigen::Vector3d::UnitZ();
  window.size_u_m = 2.0;
  window.size_v_m = 1.2;
  window.albedo = cv::Mat(8, 8, CV_32FC3, cv::Scalar(1, 1, 1));
  window.emission = Emission::kSky;
  window.room = 0;
  scene.quads.push_back(window);
  return scene;
}

// The sun alone, low in the west-south-west (to the sun (-0.8, 0.3, 0.6)),
// 1000 lux normal to it: no sky, and no ambient term (`options` gets
// ambient_fraction and ambient_leak 0), so a surface's light is the sun's.
inline SessionLighting LowSunAlone(const Scene& scene, LightingOptions* options) {
  options->ambient_fraction = 0.0;
  options->ambient_leak = 0.0;
  SessionLighting l = ComputeSessionLighting(*options, scene, 12.0);
  l.sun_direction_in_world = Eigen::Vector3d(-0.8, 0.3, 0.6).normalized();
  l.sun_normal_lux_bgr = cv::Vec3f(1000, 1000, 1000);
  l.sky_nits_bgr = cv::Vec3f(0, 0, 0);
  return l;
}

}  // namespace duskmap
