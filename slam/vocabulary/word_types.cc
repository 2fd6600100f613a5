#include "slam/vocabulary/word_types.h"

#include <algorithm>
#include <cstring>
#include <limits>

namespace duskmap {

namespace {

// Adds the squared differences of [begin, end) (a multiple of 8 long) to 8
// independent partial sums (vectorizable without reassociating one chain).
inline void AccumulateSquares(const float* a, const float* b, int begin, int end, float part[8]) {
  for (int i = begin; i < end; i += 8) {
    for (int k = 0; k < 8; ++k) {
      const float d = a[i + k] - b[i + k];
      part[k] += d * d;
    }
  }
}

inline float Reduce(const float part[8]) {
  return ((part[0] + part[1]) + (part[2] + part[3])) + ((part[4] + part[5]) + (part[6] + part[7]));
}

// Squared L2 of `cols` floats; with a finite `bound`, stops after a block of
// 32 once the partial result reaches it. Every addend is non-negative and
// rounding is monotone, so a partial result never exceeds the full one, and
// without an early stop the result is bit-identical to the unbounded one.
// Compiled twice, for AVX2 and the baseline, chosen at load time: the 8
// partial sums are one AVX2 register or two SSE registers, with the same
// additions in the same order (no FMA), so both give identical results.
__attribute__((target_clones("avx2", "default")))
float SquaredL2(const float* a, const float* b, int cols, float bound) {
  float part[8] = {0, 0, 0, 0, 0, 0, 0, 0};
  const int vector_end = cols - cols % 8;
  constexpr int kBlock = 32;
  int i = 0;
  for (; i + kBlock <= vector_end; i += kBlock) {
    AccumulateSquares(a, b, i, i + kBlock, part);
    if (i + kBlock < cols) {
      const float partial = Reduce(part);
      if (partial >= bound) return partial;
    }
  }
  AccumulateSquares(a, b, i, vector_end, part);
  float sum = Reduce(part);
  for (i = vector_end; i < cols; ++i) {
    const float d = a[i] - b[i];
    sum += d * d;
  }
  return sum;
}

}  // namespace

float DescriptorDistanceBounded(DescriptorKind kind, const uint8_t* a, const uint8_t* b, int cols,
                                float bound) {
  if (kind != DescriptorKind::kFloat) return DescriptorDistance(kind, a, b, cols);
  return SquaredL2(reinterpret_cast<const float*>(a), reinterpret_cast<const float*>(b), cols, bound);
}

float DescriptorDistance(DescriptorKind kind, const uint8_t* a, const uint8_t* b, int cols) {
  if (kind == DescriptorKind::kFloat) {
    return SquaredL2(reinterpret_cast<const float*>(a), reinterpret_cast<const float*>(b), cols,
                     std::numeric_limits<float>::infinity());
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
