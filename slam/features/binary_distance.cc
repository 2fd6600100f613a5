#include "slam/features/binary_distance.h"

#include <cstring>

#include <emmintrin.h>

#include "slam/core/check.h"

namespace duskmap {

const char* BinaryDistanceName(BinaryDistance distance) {
  return distance == BinaryDistance::kByteL1 ? "byte_l1" : "hamming";
}

BinaryDistance ParseBinaryDistance(const std::string& name, const std::string& field) {
  if (name == "hamming") return BinaryDistance::kHamming;
  if (name == "byte_l1") return BinaryDistance::kByteL1;
  throw ConfigError(field + ": must be \"byte_l1\" or \"hamming\", got \"" + name + "\"");
}

uint32_t HammingDistance(const uint8_t* a, const uint8_t* b, int cols) {
  uint32_t bits = 0;
  int i = 0;
  for (; i + 8 <= cols; i += 8) {
    uint64_t wa, wb;
    std::memcpy(&wa, a + i, 8);
    std::memcpy(&wb, b + i, 8);
    bits += static_cast<uint32_t>(__builtin_popcountll(wa ^ wb));
  }
  for (; i < cols; ++i) bits += static_cast<uint32_t>(__builtin_popcount(static_cast<unsigned>(a[i] ^ b[i])));
  return bits;
}

uint32_t ByteL1Distance(const uint8_t* a, const uint8_t* b, int cols) {
  // SSE2's PSADBW sums |a_i - b_i| of 8 bytes into each 64-bit half.
  __m128i sums = _mm_setzero_si128();
  int i = 0;
  for (; i + 16 <= cols; i += 16) {
    const __m128i va = _mm_loadu_si128(reinterpret_cast<const __m128i*>(a + i));
    const __m128i vb = _mm_loadu_si128(reinterpret_cast<const __m128i*>(b + i));
    sums = _mm_add_epi64(sums, _mm_sad_epu8(va, vb));
  }
  uint32_t total = static_cast<uint32_t>(_mm_cvtsi128_si32(sums)) +
                   static_cast<uint32_t>(_mm_cvtsi128_si32(_mm_unpackhi_epi64(sums, sums)));
  for (; i < cols; ++i) total += static_cast<uint32_t>(a[i] > b[i] ? a[i] - b[i] : b[i] - a[i]);
  return total;
}

}  // namespace duskmap
