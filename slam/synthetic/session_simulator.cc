#include "slam/synthetic/session_simulator.h"

#include "slam/core/random.h"

namespace duskmap {

SessionSimulator::SessionSimulator(const GeneratorConfig& config, const Scene& scene,
                                   double clock_time_h, uint64_t seed)
    : config_(config),
      scene_(scene),
      lighting_(ComputeSessionLighting(config.lighting, scene, clock_time_h)),
      radiance_(PrepareRadiance(scene, lighting_, config.lighting)),
      renderer_(scene, config.camera.Intrinsics()),
      camera_(config.camera, DeriveSeed(seed, 1)),
      depth_noise_(DeriveSeed(seed, 2)) {}

void SessionSimulator::Settle(const Rigid3d& world_from_camera, int iterations) {
  renderer_.Render(radiance_, world_from_camera, &view_);
  camera_.Settle(view_.radiance, iterations);
}

RgbdFrame SessionSimulator::Capture(const Rigid3d& world_from_camera) {
  renderer_.Render(radiance_, world_from_camera, &view_);
  RgbdFrame frame;
  frame.camera = renderer_.camera();
  frame.bgr = camera_.Capture(view_.radiance);
  frame.depth_m = SimulateDepth(config_.depth, scene_, view_, depth_noise_);
  frame.world_from_camera = world_from_camera;
  return frame;
}

}  // namespace duskmap
