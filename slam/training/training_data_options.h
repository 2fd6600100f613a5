// The options of `duskmap features training-data` (the "data" section of
// configs/dusknet.json): which training scenes are rendered, how patches are
// sampled, and which keypoint pairs count as the same surface point
// (docs/learned_descriptor.md).
#pragma once

#include <string>

#include "slam/features/patch_sampler.h"
#include "slam/synthetic/training_scenes.h"
#include "slam/training/correspondence.h"

namespace duskmap {

struct TrainingDataOptions {
  TrainingScenesOptions scenes;
  PatchSamplerOptions patch;
  int max_pairs_per_image_pair = 40;  // a seeded random subset of the matches beyond this
  // A keypoint of B matches A's predicted one (correspondence.h):
  double max_offset_px = 2.0;         // within this distance,
  double max_scale_ratio = 1.4;       // its size within this factor of the predicted size,
  double max_angle_deg = 30.0;        // its angle within this of the predicted angle;
  double occlusion_tolerance = 0.03;  // visible in B: |z - B's depth| <= this x z
  double same_time_share = 0.25;      // share of frames also paired with a later frame at the same time
  int validation_scenes = 2;          // the last scenes form the validation split
  int threads = 2;                    // scenes rendered in parallel (output identical)
  void Check() const;                 // throws ConfigError "<field>: problem"
  CorrespondenceOptions Correspondence() const;
};

// Reads a training config file: its "data" section strictly (unknown keys
// refused with their path), ignoring only the top-level "train" and
// "_comment"; a missing "data" or any other top-level key is a ConfigError
// naming the file.
TrainingDataOptions ReadTrainingDataConfig(const std::string& path);

}  // namespace duskmap
