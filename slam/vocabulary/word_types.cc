#include "slam/vocabulary/word_types.h"

#include <algorithm>
#include <cstring>

namespace duskmap {

namespace {
// Squared L2 over [begin, end) with 8 independent partial sums (vectorizable
// without reassociating one long chain).
float SquaredL2(const float* a, const float* b, int begin, int end) {
  float part[8] = {0, 0, 0, 0, 0, 0, 0, 0};
  int i = begin;
  for (; i + 8 <= end; i += 8) {
    for (int k = 0; k < 8; ++k) {
      const float d = a[i + k] - b[i + k];
      part[k] += d * d;
    }
  }
  float sum = ((part[0] + part[1]) + (part[2] + part[3])) + ((part[4] + part[5]) + (part[6] + part[7]));
  for (; i < end; ++i) {
    const float d = a[i] - b[i];
    sum += d * d;
  }
  return sum;
}
}  // namespace

float DescriptorDistanceBounded(DescriptorKind kind, const uint8_t* a, const uint8_t* b, int cols,
                                float bound) {
  if (kind != DescriptorKind::kFloat) return DescriptorDistance(kind, a, b, cols);
  const float* fa = reinterpret_cast<const float*>(a);
  const float* fb = reinterpret_cast<const float*>(b);
  constexpr int kChunk = 32;
  float sum = 0.0f;
  for (int begin = 0; begin < cols; begin += kChunk) {
    sum += SquaredL2(fa, fb, begin, std::min(cols, begin + kChunk));
    if (sum >= bound) return sum;
  }
  return sum;
}

float DescriptorDistance(DescriptorKind kind, const uint8_t* a, const uint8_t* b, int cols) {
  if (kind == DescriptorKind::kFloat) {
    return SquaredL2(reinterpret_cast<const float*>(a), reinterpret_cast<const float*>(b), 0, cols);
  }
  int bits = 0;
  int i = 0;
  for (; i + 8 <= cols; i += 8) {
    uint64_t wa, wb;
    std::memcpy(&wa, a + i, 8);
    std::memcpy(&wb, b + i, 8);
    bits += __builtin_popcountll(wa ^ wb);
  }
  for (; i < cols; ++i) bits += __builtin_popcount(static_cast<unsigned>(a[i] ^ b[i]));
  return static_cast<float>(bits);
}

}  // namespace duskmap
