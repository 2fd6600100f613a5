#include "slam/vocabulary/word_types.h"

#include <cstring>

namespace duskmap {

float DescriptorDistance(DescriptorKind kind, const uint8_t* a, const uint8_t* b, int cols) {
  if (kind == DescriptorKind::kFloat) {
    const float* fa = reinterpret_cast<const float*>(a);
    const float* fb = reinterpret_cast<const float*>(b);
    float sum = 0.0f;
    for (int i = 0; i < cols; ++i) {
      const float d = fa[i] - fb[i];
      sum += d * d;
    }
    return sum;
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
