// The scenes a learned descriptor is trained on (docs/learned_descriptor.md,
// "Held out"): apartments varied from the default dataset's by their own
// seeds (furniture arrangement drawn from the CC0 catalog, photo materials,
// wall colours, textures), dated across the year and recorded at clock
// times from full day to lamp-lit night with lamps on and off. None uses
// the default dataset's seed, furniture arrangement or sessions.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "slam/synthetic/generator_config.h"

namespace duskmap {

struct TrainingScenesOptions {
  uint64_t seed = 20261207;  // base seed of the scenes' variations; never the default dataset's
  int scenes = 10;           // scenes generated
  int hours_per_scene = 4;   // clock times per scene, spread from day to night
  int frames_per_hour = 96;  // route frames rendered at each clock time (10 scenes: about 280,000 pairs)
  void Check() const;        // throws ConfigError "<field>: problem"
};

// One training scene: the generator config it is rendered with (the default
// model's values with this scene's variations) and its clock times.
// Its config: a seed of its own; scene.seed = DeriveSeed(seed, 1), the
// texture seed GenerateDataset gives it too; scene.wall_paint_seed; the
// furniture of training_furniture.h; photo materials in three scenes of
// five; a date spread over the year (a golden-ratio sequence); sessions
// "1".."N" (mapping) from full day (10:00-15:00) through sunset to lamp-lit
// night (75 minutes after sunset to 23:00); the floor lamp on from around
// sunset, each ceiling light on in half the scenes, lamps of 2500-3500 K;
// the camera model's defaults. max_frames = frames_per_hour, and
// route.frame_rate_hz such that those first frames span the whole patrol
// route (rather than its first rooms).
struct TrainingScene {
  int index = 0;
  GeneratorConfig config;           // its sessions: one per clock time
  std::string furniture_signature;  // its arrangement, canonical text (held-out checks)
};

// Scene `index` (0 <= index < options.scenes) of the set `options` defines.
// Deterministic. Never has the default dataset's seed, arrangement or sessions.
TrainingScene MakeTrainingScene(const TrainingScenesOptions& options, int index);

// The canonical text of a furniture arrangement (model, room, position, yaw,
// elevation of each piece, in order), to compare arrangements.
std::string FurnitureSignature(const FurnitureOptions& furniture);

}  // namespace duskmap
