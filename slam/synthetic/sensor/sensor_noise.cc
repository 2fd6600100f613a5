#include "slam/synthetic/sensor/sensor_noise.h"

#include <cmath>
#include <vector>

#include "slam/core/random.h"

namespace duskmap {
namespace {

constexpr int kTableSize = 65536;

// Standard normal quantile by bisection on the CDF 0.5 * erfc(-x / sqrt(2)):
// slow but exact to float precision; the table is built once per process.
float Quantile(double p) {
  double lo = -9.0, hi = 9.0;
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (0.5 * std::erfc(-mid / std::sqrt(2.0)) < p) lo = mid;
    else hi = mid;
  }
  return static_cast<float>(0.5 * (lo + hi));
}

const std::vector<float>& NormalTable() {
  static const std::vector<float> table = [] {
    std::vector<float> t(kTableSize);
    // Symmetric by construction: compute the upper half, mirror it.
    for (int i = kTableSize / 2; i < kTableSize; ++i) {
      t[i] = Quantile((i + 0.5) / kTableSize);
      t[kTableSize - 1 - i] = -t[i];
    }
    return t;
  }();
  return table;
}

}  // namespace

SensorNoise::SensorNoise(uint64_t seed) : state_(DeriveSeed(seed, 0x5e45) | 1) {}

float SensorNoise::NormalQuantile(uint16_t index) { return NormalTable()[index]; }

void SensorNoise::FillNormal(float* out, size_t count) {
  const float* table = NormalTable().data();
  size_t i = 0;
  for (; i + 4 <= count; i += 4) {
    const uint64_t r = Next();
    out[i] = table[r & 0xFFFF];
    out[i + 1] = table[(r >> 16) & 0xFFFF];
    out[i + 2] = table[(r >> 32) & 0xFFFF];
    out[i + 3] = table[r >> 48];
  }
  if (i < count) {
    uint64_t r = Next();
    for (; i < count; ++i, r >>= 16) out[i] = table[r & 0xFFFF];
  }
}

void SensorNoise::FillUniform(float* out, size_t count) {
  constexpr float kScale = 1.0f / 4294967296.0f;  // 2^-32
  size_t i = 0;
  for (; i + 2 <= count; i += 2) {
    const uint64_t r = Next();
    // 24 significant bits each, so the float is exactly representable and < 1.
    out[i] = static_cast<float>((r & 0xFFFFFF00ull) >> 8) * (kScale * 256.0f);
    out[i + 1] = static_cast<float>((r >> 40)) * (kScale * 256.0f);
  }
  if (i < count) out[i] = static_cast<float>((Next() & 0xFFFFFF00ull) >> 8) * (kScale * 256.0f);
}

}  // namespace duskmap
