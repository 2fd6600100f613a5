// A tiny synthetic dataset for the engine's tests (default 640x480 camera, the
// first 25 frames of the patrol route), rendered once per build and shared by
// the test processes (tests/testing/fixture_cache.h). Read-only: tests write
// into testing::ProcessTempDir.
#pragma once

#include <string>

#include "slam/io/synthetic_dataset.h"
#include "slam/synthetic/generator.h"
#include "tests/testing/fixture_cache.h"
#include "tests/testing/temp_dir.h"

namespace duskmap::testing {

// Mapping sessions "1" (16:46), "2" (16:56) and "6" (19:35); localization
// sessions "A" (16:51) and "F" (19:42).
inline const std::string& TinyDatasetPath() {
  static const std::string path = CachedFixture("engine_tiny_dataset", [](const std::string& p) {
    // The box apartment without motion blur, on which the engine's bounds
    // were measured.
    GeneratorConfig config;
    ApplyGeneratorModel("boxes-2026-12-02", &config);
    config.camera.exposure.motion_blur_scale = 0.0;
    // 640x480: at 320x240 SURF registration accepted transforms 5-9 deg off
    // and re-localized only 63 % of same-light frames (measured).
    config.max_frames = 25;
    config.threads = 2;
    config.sessions = {{"1", "16:46", "mapping"},
                       {"2", "16:56", "mapping"},
                       {"6", "19:35", "mapping"},
                       {"A", "16:51", "localization"},
                       {"F", "19:42", "localization"}};
    GenerateOptions options;
    options.output_path = p;
    options.overwrite = true;
    GenerateDataset(config, options);
  });
  return path;
}

}  // namespace duskmap::testing
