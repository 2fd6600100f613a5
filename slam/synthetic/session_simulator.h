// One recording session of the synthetic apartment: its light state, its
// prepared radiance textures (the lighting preparation, done once), the
// renderer, the stateful camera and the depth sensor. Frames are produced in
// order because the camera's auto-exposure and white balance carry over.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "slam/core/rgbd_frame.h"
#include "slam/synthetic/generator_config.h"
#include "slam/synthetic/light/lighting.h"
#include "slam/synthetic/render/renderer.h"
#include "slam/synthetic/sensor/camera_model.h"
#include "slam/synthetic/sensor/depth_sensor.h"

namespace duskmap {

class SessionSimulator {
 public:
  // Prepares the lighting of the session at `clock_time_h` on the date `day`
  // days after config.lighting's day_of_year (SessionSpec::day; the sun's
  // path of that date, LightingOnDay); `seed` drives camera and depth noise.
  SessionSimulator(const GeneratorConfig& config, const Scene& scene, double clock_time_h, uint64_t seed,
                   int day = 0);

  // Renders the frame seen from world_from_camera and runs the camera on it.
  // The returned frame has bgr, depth_m, camera and world_from_camera set.
  RgbdFrame Capture(const Rigid3d& world_from_camera);
  // Meters the view several times (the camera running before recording).
  void Settle(const Rigid3d& world_from_camera, int iterations);

  const LightingOptions& lighting_options() const { return lighting_options_; }  // of the session's day
  const SessionLighting& lighting() const { return lighting_; }
  const SessionRadiance& radiance() const { return radiance_; }
  const Renderer& renderer() const { return renderer_; }
  const CameraModel& camera() const { return camera_; }
  const RenderedView& last_view() const { return view_; }

 private:
  const GeneratorConfig& config_;
  const Scene& scene_;
  LightingOptions lighting_options_;
  SessionLighting lighting_;
  SessionRadiance radiance_;
  Renderer renderer_;
  CameraModel camera_;
  SensorNoise depth_noise_;
  RenderedView view_;
  std::optional<Rigid3d> last_world_from_camera_;  // previous frame (or settle) pose
};

// `options` on the date `day` (>= 0) days later: site.day_of_year advanced
// by DayOfYearAfter (past the year's end, into the next year). Day 0 is
// `options` unchanged.
LightingOptions LightingOnDay(const LightingOptions& options, int day);

// Image velocity (pixels/s, x and y) at the image centre when the camera
// turns from `previous` to `current` at a constant rate over `interval_s`
// (rotation only: the translation of a walking person moves the image far
// less than turning).
cv::Vec2d ImageVelocityPxPerS(const Rigid3d& previous_world_from_camera, const Rigid3d& current_world_from_camera,
                              const PinholeCamera& camera, double interval_s);

}  // namespace duskmap
