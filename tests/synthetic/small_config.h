// A small, fast generator configuration for tests: the box apartment
// (boxes-2026-12-02) without motion blur, 160x120 images, a few frames per
// session, coarse light maps.
#pragma once

#include "slam/synthetic/generator_config.h"

namespace duskmap::testing {

inline GeneratorConfig SmallConfig(int max_frames = 3) {
  GeneratorConfig config;
  ApplyGeneratorModel("boxes-2026-12-02", &config);
  config.camera.exposure.motion_blur_scale = 0.0;
  config.camera.width = 160;
  config.camera.height = 120;
  config.camera.fx = config.camera.fy = 131.25;
  config.lighting.light_texel_m = 0.25;
  config.max_frames = max_frames;
  config.threads = 2;
  config.sessions = {{"1", "16:46", "mapping"}, {"F", "19:42", "localization"}};
  return config;
}

}  // namespace duskmap::testing
