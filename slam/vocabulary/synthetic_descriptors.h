// Synthetic descriptors for tests and benchmarks: each landmark has a
// deterministic random prototype (SIFT-like 128 floats in [0, 1), or
// ORB/BRIEF-like 32 bytes); an observation adds noise, and a change of
// appearance (e.g. lighting of another session) replaces a landmark's
// prototype with another one with a given probability.
#pragma once

#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

#include "slam/features/frame_features.h"

namespace duskmap {

struct SyntheticDescriptorOptions {
  DescriptorKind kind = DescriptorKind::kFloat;
  int cols = 128;                    // floats (float kind) or bytes (binary kind) per row
  double float_noise_sigma = 0.02;   // per-element Gaussian noise of an observation (float)
  double bit_flip_probability = 0.04;  // per-bit flip probability of an observation (binary)
  uint64_t seed = 1;                 // prototypes derive from it

  void Check() const;
};

class SyntheticDescriptors {
 public:
  explicit SyntheticDescriptors(const SyntheticDescriptorOptions& options);

  // One row per landmark, in order. Under `appearance` a (landmark,
  // appearance) pair keeps the landmark's base prototype with probability
  // `keep_probability` (deterministic in the pair), else it has a prototype
  // of its own; appearance 0 always uses the base. `observation_seed`
  // drives the noise of this observation.
  cv::Mat Observe(const std::vector<int64_t>& landmarks, int appearance, double keep_probability,
                  uint64_t observation_seed) const;
  // Fully random rows (a frame of never-seen structure).
  cv::Mat Random(int rows, uint64_t seed) const;
  FrameFeatures ToFeatures(const cv::Mat& descriptors) const;

 private:
  void Prototype(uint64_t stream, uint8_t* row) const;

  SyntheticDescriptorOptions options_;
};

}  // namespace duskmap
