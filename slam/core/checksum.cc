#include "slam/core/checksum.h"

#include <cstdio>
#include <cstring>

namespace duskmap {

uint64_t Checksum64(const void* data, size_t bytes) {
  // FNV-1a over 8-byte words (then the tail bytes), with a final mix: the
  // byte-wise FNV-1a's dispersion at an eighth of its steps.
  const uint8_t* p = static_cast<const uint8_t*>(data);
  constexpr uint64_t kPrime = 0x100000001b3ull;
  uint64_t h = 0xcbf29ce484222325ull ^ bytes;
  size_t i = 0;
  for (; i + 8 <= bytes; i += 8) {
    uint64_t word;
    std::memcpy(&word, p + i, 8);
    h = (h ^ word) * kPrime;
    h ^= h >> 29;
  }
  for (; i < bytes; ++i) h = (h ^ p[i]) * kPrime;
  h ^= h >> 33;
  h *= 0xff51afd7ed558ccdull;
  h ^= h >> 33;
  return h;
}

std::string Checksum64Hex(const void* data, size_t bytes) {
  char text[17];
  std::snprintf(text, sizeof(text), "%016llx",
                static_cast<unsigned long long>(Checksum64(data, bytes)));
  return text;
}

}  // namespace duskmap
