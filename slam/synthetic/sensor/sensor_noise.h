// Fast seeded noise for the simulated sensors. A frame needs about 1.2
// million normal samples (colour shot/read noise and depth noise); OpenCV's
// cv::RNG::fill took a quarter of the frame time. Here one 64-bit xorshift*
// draw gives four 16-bit indices into a table of 65536 normal quantiles
// (inverse CDF at (i + 0.5) / 65536, i.e. a standard normal truncated at
// 4.3 sigma with 16-bit resolution), which is plenty for sensor noise.
// Deterministic: the same seed gives the same sequence on every platform.
#pragma once

#include <cstddef>
#include <cstdint>

namespace duskmap {

class SensorNoise {
 public:
  explicit SensorNoise(uint64_t seed);

  // Fills out[0..count) with standard-normal samples.
  void FillNormal(float* out, size_t count);
  // Fills out[0..count) with uniform samples in [0, 1).
  void FillUniform(float* out, size_t count);

  // The table value for a 16-bit index (the quantile at (index + 0.5) / 65536).
  static float NormalQuantile(uint16_t index);

 private:
  uint64_t Next() {
    state_ ^= state_ >> 12;
    state_ ^= state_ << 25;
    state_ ^= state_ >> 27;
    return state_ * 0x2545F4914F6CDD1Dull;
  }

  uint64_t state_;
};

}  // namespace duskmap
