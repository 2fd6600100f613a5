// The patrol route walked in every session: a person holding the camera at
// 1.2-1.4 m walks the waypoints at about 0.38 m/s (the pace that gives the
// paper's 201 frames per single-session map on average), turns in place at
// some of them, with natural sway; each session deviates from the route like
// a person repeating it (smooth lateral offsets with the distance walked,
// heading offsets, speed). The walker keeps its session speed along the path
// it actually walks, so no step between consecutive frames is longer than
// max_step_m: the paper's 55 cm at 1 Hz ("the maximum distance between two
// consecutive frames taken at 1 Hz while walking at 55 cm per second").
// Frames are sampled at frame_rate_hz; the poses are ground truth
// world_from_camera.
#pragma once

#include <cstdint>
#include <vector>

#include "slam/core/rigid3.h"
#include "slam/synthetic/scene/apartment.h"

namespace duskmap {

struct RouteOptions {
  double speed_mps = 0.38;          // nominal walking speed along the walked path
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
  double max_step_m = 0.55;         // largest camera move between consecutive frames
  // true: the walker keeps its speed along the path it walks, the wander a
  // function of the distance walked (run 24 on). false: the models up to run
  // 23, the wander a function of time added to the nominal walk, so a step
  // may exceed speed / frame rate (their max_step_m is 1 m).
  bool paced_walk = true;

  // The largest camera move between consecutive frames that a paced walk
  // allows: the fastest session's walk in one frame period, with the bob.
  double LargestStepBoundM() const;
  // Throws ConfigError naming the key; a paced walk that could step further
  // than max_step_m is refused here, before anything is generated.
  void Check() const;
};

struct TimedPose {
  double time_s = 0.0;  // since the session start
  Rigid3d world_from_camera;
};

// The route's ground-truth camera poses for one session (seeded deviations;
// seed 0 with zero deviations in the options gives the nominal route).
// Throws ConfigError naming route.max_step_m when a step is longer (possible
// only without paced_walk).
std::vector<TimedPose> GenerateRoute(const RouteOptions& options,
                                     const std::vector<RouteWaypoint>& waypoints, uint64_t seed);

// The largest camera move between consecutive poses of a route, metres.
double LargestStepM(const std::vector<TimedPose>& route);

}  // namespace duskmap
