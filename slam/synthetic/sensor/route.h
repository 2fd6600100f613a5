// The patrol route walked in every session: a person holding the camera at
// 1.2-1.4 m walks the waypoints at about 0.55 m/s, turns in place at some of
// them, with natural sway; each session deviates from the nominal route like
// a person repeating it (smooth lateral offsets, heading offsets, speed).
// Frames are sampled at frame_rate_hz; the poses are ground truth
// world_from_camera.
#pragma once

#include <cstdint>
#include <vector>

#include "slam/core/rigid3.h"
#include "slam/synthetic/scene/apartment.h"

namespace duskmap {

struct RouteOptions {
  double speed_mps = 0.55;          // nominal walking speed
  double turn_speed_dps = 20.0;     // in-place rotation speed, deg/s
  double corner_turn_speed_dps = 60.0;  // turning at corners, deg/s
  double frame_rate_hz = 1.0;       // recorded frames per second
  double height_m = 1.3;            // nominal camera height
  double height_spread_m = 0.08;    // per-session height offset, uniform +-
  double lateral_max_m = 0.2;       // largest offset from the nominal path
  double heading_max_deg = 5.0;     // largest heading offset
  double speed_variation = 0.10;    // per-session speed factor, uniform 1 +- this
  double sway_deg = 1.5;            // pitch/roll sway amplitude
  double bob_m = 0.015;             // vertical bob amplitude
  double pitch_deg = -4.0;          // mean pitch (negative: looking slightly down)

  void Check() const;
};

struct TimedPose {
  double time_s = 0.0;  // since the session start
  Rigid3d world_from_camera;
};

// The route's ground-truth camera poses for one session (seeded deviations;
// seed 0 with zero deviations in the options gives the nominal route).
std::vector<TimedPose> GenerateRoute(const RouteOptions& options,
                                     const std::vector<RouteWaypoint>& waypoints, uint64_t seed);

}  // namespace duskmap
