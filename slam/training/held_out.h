// The held-out rule of the learned descriptor's training data
// (docs/learned_descriptor.md): no training scene shares the default
// dataset's generator seed, its texture seed or its furniture arrangement.
#pragma once

#include <cstdint>

#include "slam/synthetic/training_scenes.h"

namespace duskmap {

// The texture seed a scene's apartment is built with (the generator derives
// it from the config's seed: GeneratorSceneOptions).
uint64_t SceneTextureSeed(const GeneratorConfig& config);

// Throws ConfigError "training scene <index>: <what> is the default
// dataset's (...)" when the scene breaks the rule.
void CheckHeldOut(const TrainingScene& scene);

}  // namespace duskmap
