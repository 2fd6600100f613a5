// `duskmap features training-data`: renders every training scene's pairs
// (training_pairs.h) on options.threads threads, one scene per thread, and
// writes them in scene order into a training-data folder
// (training_data_files.h); the output is identical for any thread count.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include "slam/training/training_data_files.h"
#include "slam/training/training_data_options.h"

namespace duskmap {

struct TrainingDataRunOptions {
  std::string output_path;  // folder to create
  bool overwrite = false;   // replace training data duskmap wrote
};

// One scene written (in index order).
struct TrainingSceneProgress {
  int index = 0;
  int scenes = 0;
  std::string split;
  int frames = 0;
  int image_pairs = 0;
  int64_t pairs = 0;
  double wall_s = 0.0;  // rendering and matching the scene
};

struct TrainingDataSummary {
  TrainingDataManifest manifest;
  std::string output_path;
  double wall_s = 0.0;
};

TrainingDataSummary GenerateTrainingData(const TrainingDataOptions& options, const TrainingDataRunOptions& run,
                                         const std::function<void(const TrainingSceneProgress&)>& progress);

}  // namespace duskmap
