// The training pairs of one training scene (docs/learned_descriptor.md):
// the apartment built once, one session per clock time, each capturing the
// scene's route's first frames_per_hour frames; SIFT's keypoints (the `sift`
// type, default options, 1,000 strongest) detected on each captured gray
// image, matched between two frames through the renderer's exact depth and
// the poses (correspondence.h), and both patches of each match sampled by
// the PatchSampler that inference uses.
#pragma once

#include <cstdint>
#include <vector>

#include "slam/synthetic/training_scenes.h"
#include "slam/training/training_data_options.h"

namespace duskmap {

// Frame frame_a at clock time time_a paired with frame_b at time_b
// (indices into the scene's sessions and its route's frames).
struct ImagePair {
  int time_a = 0;
  int frame_a = 0;
  int time_b = 0;
  int frame_b = 0;
};

// For every ordered pair of times a != b and every frame i: (i at a, i + d
// at b), d drawn from {0, 1, 2} when a < b and from {1, 2} when a > b (so no
// pair of the same two images appears twice); plus, for a share of the
// frames at each time, (i at a, i + d at a) with d in {1, 2}. Pairs whose
// later frame is beyond `frames` are left out. Deterministic in `seed`.
std::vector<ImagePair> SelectImagePairs(int times, int frames, double same_time_share, uint64_t seed);

struct ScenePairs {
  int scene_index = 0;
  int64_t pairs = 0;
  std::vector<uint8_t> patches;         // pairs x 2 x P x P: A's patch, then B's
  std::vector<float> points_in_world;   // pairs x 3, metres: A's surface point
  int frames = 0;                       // frames rendered (all times)
  int image_pairs = 0;                  // image pairs matched
  double wall_s = 0.0;
};

// Renders scene `scene` and returns its pairs. Deterministic.
ScenePairs RenderScenePairs(const TrainingScene& scene, const TrainingDataOptions& options);

}  // namespace duskmap
