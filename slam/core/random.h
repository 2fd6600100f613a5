// Seeded random numbers. Every stochastic algorithm takes a seed through its
// options and owns its generator, so results are reproducible run to run.
#pragma once

#include <cstdint>
#include <random>

namespace duskmap {

using Rng = std::mt19937_64;

// Derives an independent, reproducible seed for a named sub-stream
// (e.g. the noise of session "3") from a base seed (splitmix64 mixing).
inline uint64_t DeriveSeed(uint64_t base, uint64_t stream) {
  uint64_t z = base + 0x9E3779B97F4A7C15ull * (stream + 1);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

}  // namespace duskmap
