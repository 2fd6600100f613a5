#include "slam/training/held_out.h"

#include "slam/core/check.h"
#include "slam/synthetic/generator.h"

namespace duskmap {

uint64_t SceneTextureSeed(const GeneratorConfig& config) { return GeneratorSceneOptions(config).seed; }

void CheckHeldOut(const TrainingScene& scene) {
  const GeneratorConfig reference;  // the default dataset
  SLAM_THROW_IF_NOT(ConfigError, scene.config.seed != reference.seed)
      << "training scene " << scene.index << ": its seed " << scene.config.seed
      << " is the default dataset's (held out: never train on it)";
  SLAM_THROW_IF_NOT(ConfigError, SceneTextureSeed(scene.config) != SceneTextureSeed(reference))
      << "training scene " << scene.index << ": its texture seed " << SceneTextureSeed(scene.config)
      << " is the default dataset's (held out: never train on it)";
  SLAM_THROW_IF_NOT(ConfigError, FurnitureSignature(scene.config.scene.furniture) !=
                                     FurnitureSignature(reference.scene.furniture))
      << "training scene " << scene.index
      << ": its furniture arrangement is the default dataset's (held out: never train on it)";
}

}  // namespace duskmap
