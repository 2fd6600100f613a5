#include "slam/vocabulary/word_types.h"

#include <algorithm>
#include <cstring>
#include <limits>

#include <immintrin.h>

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

// The sum of squares behind both distances below: `add_blocks(begin, end,
// part)` adds the squared differences of [begin, end) (a multiple of 8 long)
// to the 8 partial sums, `square(i)` is the squared difference of element i
// past the last 8-wide block. With a finite `bound` it stops after a block of
// 32 once the partial result reaches it. Every addend is non-negative and
// rounding is monotone, so a partial result never exceeds the full one, and
// without an early stop the result is bit-identical to the unbounded one.
template <typename AddBlocks, typename Square>
inline float BoundedSumOfSquares(int cols, float bound, AddBlocks add_blocks, Square square) {
  float part[8] = {0, 0, 0, 0, 0, 0, 0, 0};
  const int vector_end = cols - cols % 8;
  constexpr int kBlock = 32;
  int i = 0;
  for (; i + kBlock <= vector_end; i += kBlock) {
    add_blocks(i, i + kBlock, part);
    if (i + kBlock < cols) {
      const float partial = Reduce(part);
      if (partial >= bound) return partial;
    }
  }
  add_blocks(i, vector_end, part);
  float sum = Reduce(part);
  for (i = vector_end; i < cols; ++i) sum += square(i);
  return sum;
}

// Squared L2 of `cols` floats, bounded as above. Compiled twice, for AVX2 and
// the baseline, chosen at load time: the 8 partial sums are one AVX2 register
// or two SSE registers, with the same additions in the same order (no FMA),
// so both give identical results.
__attribute__((target_clones("avx2", "default")))
float SquaredL2(const float* a, const float* b, int cols, float bound) {
  return BoundedSumOfSquares(
      cols, bound, [a, b](int begin, int end, float* part) { AccumulateSquares(a, b, begin, end, part); },
      [a, b](int i) {
        const float d = a[i] - b[i];
        return d * d;
      });
}

// The same with the second row quantized: b[i] = offset + step * codes[i],
// computed as DequantizeRow does (a product, then a sum; no FMA), with the
// 8 partial sums of SquaredL2 in the same order, so that the result is the
// float distance to the decoded row bit for bit. Written with intrinsics:
// GCC's auto-vectorization of the byte-to-float conversion used 2-wide
// steps and made the 1,200-node LCD 25 % slower than with float rows.
// Returns the block's partial sums added to part[0..8).
__attribute__((target("avx2")))
void QuantizedBlocksAvx2(const float* a, const uint8_t* codes, float offset, float step, int begin,
                         int end, float part[8]) {
  __m256 acc = _mm256_loadu_ps(part);
  const __m256 off = _mm256_set1_ps(offset), st = _mm256_set1_ps(step);
  for (int i = begin; i < end; i += 8) {
    const __m128i c8 = _mm_loadl_epi64(reinterpret_cast<const __m128i*>(codes + i));
    const __m256 c = _mm256_cvtepi32_ps(_mm256_cvtepu8_epi32(c8));
    const __m256 d = _mm256_sub_ps(_mm256_loadu_ps(a + i), _mm256_add_ps(off, _mm256_mul_ps(st, c)));
    acc = _mm256_add_ps(acc, _mm256_mul_ps(d, d));
  }
  _mm256_storeu_ps(part, acc);
}

void QuantizedBlocksSse2(const float* a, const uint8_t* codes, float offset, float step, int begin,
                         int end, float part[8]) {
  __m128 lo = _mm_loadu_ps(part), hi = _mm_loadu_ps(part + 4);
  const __m128 off = _mm_set1_ps(offset), st = _mm_set1_ps(step);
  const __m128i zero = _mm_setzero_si128();
  for (int i = begin; i < end; i += 8) {
    const __m128i c16 = _mm_unpacklo_epi8(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(codes + i)), zero);
    const __m128 c_lo = _mm_cvtepi32_ps(_mm_unpacklo_epi16(c16, zero));
    const __m128 c_hi = _mm_cvtepi32_ps(_mm_unpackhi_epi16(c16, zero));
    const __m128 d_lo = _mm_sub_ps(_mm_loadu_ps(a + i), _mm_add_ps(off, _mm_mul_ps(st, c_lo)));
    const __m128 d_hi = _mm_sub_ps(_mm_loadu_ps(a + i + 4), _mm_add_ps(off, _mm_mul_ps(st, c_hi)));
    lo = _mm_add_ps(lo, _mm_mul_ps(d_lo, d_lo));
    hi = _mm_add_ps(hi, _mm_mul_ps(d_hi, d_hi));
  }
  _mm_storeu_ps(part, lo);
  _mm_storeu_ps(part + 4, hi);
}

using QuantizedBlocksFn = void (*)(const float*, const uint8_t*, float, float, int, int, float*);

QuantizedBlocksFn SelectQuantizedBlocks() {
  __builtin_cpu_init();
  return __builtin_cpu_supports("avx2") ? QuantizedBlocksAvx2 : QuantizedBlocksSse2;
}

float QuantizedSquaredL2With(QuantizedBlocksFn blocks, const float* a, const uint8_t* codes,
                             float offset, float step, int cols, float bound) {
  return BoundedSumOfSquares(
      cols, bound,
      [=](int begin, int end, float* part) { blocks(a, codes, offset, step, begin, end, part); },
      [=](int i) {
        const float d = a[i] - (offset + step * static_cast<float>(codes[i]));
        return d * d;
      });
}

float QuantizedSquaredL2(const float* a, const uint8_t* codes, float offset, float step, int cols,
                         float bound) {
  static const QuantizedBlocksFn blocks = SelectQuantizedBlocks();
  return QuantizedSquaredL2With(blocks, a, codes, offset, step, cols, bound);
}

RowScale StoredScale(const uint8_t* stored) {
  RowScale scale;
  std::memcpy(&scale.offset, stored, sizeof(float));
  std::memcpy(&scale.step, stored + sizeof(float), sizeof(float));
  return scale;
}

constexpr size_t kScaleBytes = 2 * sizeof(float);

}  // namespace

WordRowFormat WordRowFormatFor(DescriptorKind kind, DescriptorStorage float_storage) {
  if (kind == DescriptorKind::kBinary) return WordRowFormat::kBinary;
  return float_storage == DescriptorStorage::kUint8 ? WordRowFormat::kQuantized8
                                                    : WordRowFormat::kFloat32;
}

size_t WordRowBytes(WordRowFormat format, int cols) {
  switch (format) {
    case WordRowFormat::kFloat32: return static_cast<size_t>(cols) * sizeof(float);
    case WordRowFormat::kQuantized8: return kScaleBytes + static_cast<size_t>(cols);
    case WordRowFormat::kBinary: return static_cast<size_t>(cols);
  }
  return 0;
}

size_t QueryRowBytes(WordRowFormat format, int cols) {
  return format == WordRowFormat::kBinary ? static_cast<size_t>(cols)
                                          : static_cast<size_t>(cols) * sizeof(float);
}

bool EncodeWordRow(WordRowFormat format, const uint8_t* descriptor, int cols, uint8_t* stored) {
  if (format != WordRowFormat::kQuantized8) {
    std::memcpy(stored, descriptor, WordRowBytes(format, cols));
    return true;
  }
  RowScale scale;
  if (!QuantizeRow(reinterpret_cast<const float*>(descriptor), cols, stored + kScaleBytes, &scale)) {
    return false;
  }
  StoreQuantizedWordRow(stored + kScaleBytes, scale, cols, stored);
  return true;
}

void StoreQuantizedWordRow(const uint8_t* codes, RowScale scale, int cols, uint8_t* stored) {
  std::memcpy(stored, &scale.offset, sizeof(float));
  std::memcpy(stored + sizeof(float), &scale.step, sizeof(float));
  // EncodeWordRow quantizes straight into place: nothing to copy then.
  if (stored + kScaleBytes != codes) std::memcpy(stored + kScaleBytes, codes, cols);
}

void DecodeWordRow(WordRowFormat format, const uint8_t* stored, int cols, uint8_t* descriptor) {
  if (format != WordRowFormat::kQuantized8) {
    std::memcpy(descriptor, stored, WordRowBytes(format, cols));
    return;
  }
  DequantizeRow(stored + kScaleBytes, cols, StoredScale(stored), reinterpret_cast<float*>(descriptor));
}

int WordRowDims(WordRowFormat format, int cols, BinaryDistance binary) {
  return format == WordRowFormat::kBinary && binary == BinaryDistance::kHamming ? cols * 8 : cols;
}

float WordRowValue(WordRowFormat format, const uint8_t* stored, int dim, BinaryDistance binary) {
  switch (format) {
    case WordRowFormat::kFloat32: {
      float v;
      std::memcpy(&v, stored + static_cast<size_t>(dim) * sizeof(float), sizeof(float));
      return v;
    }
    case WordRowFormat::kQuantized8: {
      const RowScale scale = StoredScale(stored);
      return scale.offset + scale.step * static_cast<float>(stored[kScaleBytes + dim]);
    }
    case WordRowFormat::kBinary:
      if (binary == BinaryDistance::kByteL1) return static_cast<float>(stored[dim]);
      return static_cast<float>((stored[dim >> 3] >> (dim & 7)) & 1);
  }
  return 0.0f;
}

float WordDistanceBounded(WordRowFormat format, const uint8_t* query, const uint8_t* stored,
                          int cols, float bound, BinaryDistance binary) {
  switch (format) {
    case WordRowFormat::kFloat32:
      return DescriptorDistanceBounded(DescriptorKind::kFloat, query, stored, cols, bound);
    case WordRowFormat::kQuantized8: {
      const RowScale scale = StoredScale(stored);
      return QuantizedSquaredL2(reinterpret_cast<const float*>(query), stored + kScaleBytes,
                                scale.offset, scale.step, cols, bound);
    }
    case WordRowFormat::kBinary:
      return DescriptorDistance(DescriptorKind::kBinary, query, stored, cols, binary);
  }
  return 0.0f;
}

namespace detail {
float QuantizedWordDistanceBaselineSimd(const uint8_t* query, const uint8_t* stored, int cols) {
  const RowScale scale = StoredScale(stored);
  return QuantizedSquaredL2With(QuantizedBlocksSse2, reinterpret_cast<const float*>(query),
                                stored + kScaleBytes, scale.offset, scale.step, cols,
                                std::numeric_limits<float>::infinity());
}
}  // namespace detail

float WordDistance(WordRowFormat format, const uint8_t* query, const uint8_t* stored, int cols,
                   BinaryDistance binary) {
  return WordDistanceBounded(format, query, stored, cols, std::numeric_limits<float>::infinity(),
                             binary);
}

float DescriptorDistanceBounded(DescriptorKind kind, const uint8_t* a, const uint8_t* b, int cols,
                                float bound, BinaryDistance binary) {
  if (kind != DescriptorKind::kFloat) return DescriptorDistance(kind, a, b, cols, binary);
  return SquaredL2(reinterpret_cast<const float*>(a), reinterpret_cast<const float*>(b), cols, bound);
}

float DescriptorDistance(DescriptorKind kind, const uint8_t* a, const uint8_t* b, int cols,
                         BinaryDistance binary) {
  if (kind == DescriptorKind::kFloat) {
    return SquaredL2(reinterpret_cast<const float*>(a), reinterpret_cast<const float*>(b), cols,
                     std::numeric_limits<float>::infinity());
  }
  return static_cast<float>(BinaryRowDistance(binary, a, b, cols));
}

}  // namespace duskmap
