#include "slam/synthetic/session_simulator.h"

#include "slam/core/random.h"

namespace duskmap {

LightingOptions LightingOnDay(const LightingOptions& options, int day) {
  LightingOptions on_day = options;
  on_day.site.day_of_year = DayOfYearAfter(options.site.day_of_year, day);
  return on_day;
}

SessionSimulator::SessionSimulator(const GeneratorConfig& config, const Scene& scene,
                                   double clock_time_h, uint64_t seed, int day)
    : config_(config),
      scene_(scene),
      lighting_options_(LightingOnDay(config.lighting, day)),
      lighting_(ComputeSessionLighting(lighting_options_, scene, clock_time_h)),
      radiance_(PrepareSessionRadiance(scene, lighting_, lighting_options_)),
      renderer_(scene, config.camera.Intrinsics()),
      camera_(config.camera, DeriveSeed(seed, 1)),
      depth_noise_(DeriveSeed(seed, 2)) {}

cv::Vec2d ImageVelocityPxPerS(const Rigid3d& previous, const Rigid3d& current, const PinholeCamera& camera,
                              double interval_s) {
  if (interval_s <= 0.0) return cv::Vec2d(0, 0);
  // Angular velocity in the camera frame (constant over the interval); at the
  // image centre a turn about the camera's y axis moves the image along x by
  // fx pixels per radian, a turn about x moves it along y by fy.
  const Eigen::AngleAxisd turn(current.rotation.inverse() * previous.rotation);
  const Eigen::Vector3d omega = turn.axis() * turn.angle() / interval_s;
  return cv::Vec2d(camera.fx * omega.y(), -camera.fy * omega.x());
}

void SessionSimulator::Settle(const Rigid3d& world_from_camera, int iterations) {
  renderer_.Render(radiance_, world_from_camera, &view_);
  camera_.Settle(view_.radiance, iterations);
  last_world_from_camera_ = world_from_camera;
}

RgbdFrame SessionSimulator::Capture(const Rigid3d& world_from_camera) {
  renderer_.Render(radiance_, world_from_camera, &view_);
  RgbdFrame frame;
  frame.camera = renderer_.camera();
  const cv::Vec2d velocity =
      last_world_from_camera_
          ? ImageVelocityPxPerS(*last_world_from_camera_, world_from_camera, renderer_.camera(),
                                1.0 / config_.route.frame_rate_hz)
          : cv::Vec2d(0, 0);
  last_world_from_camera_ = world_from_camera;
  frame.bgr = camera_.Capture(view_.radiance, velocity);
  frame.depth_m = SimulateDepth(config_.depth, scene_, view_, depth_noise_);
  frame.world_from_camera = world_from_camera;
  return frame;
}

}  // namespace duskmap
