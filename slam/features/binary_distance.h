// How binary descriptors are compared (issue 23). The reference compares them
// in its KD-trees after turning bytes into floats: with Kp/ByteToFloat false
// (its default) each bit becomes a float and L1 is the Hamming distance; with
// Kp/ByteToFloat true (the paper's runs) each byte becomes one float and the
// KD-trees compare the byte values by L1, in the vocabulary and in
// registration's first-pass matching (Vis/CorNNType 1). Brute-force and LSH
// matching, and the guess-window matching of the second pass, stay Hamming.
#pragma once

#include <cstdint>
#include <string>

namespace duskmap {

enum class BinaryDistance {
  kHamming,  // bits that differ
  kByteL1,   // sum over bytes of |a_i - b_i| (0..255 each)
};

const char* BinaryDistanceName(BinaryDistance distance);  // "hamming", "byte_l1"
// Parses a name; throws ConfigError naming `field` and the accepted values.
BinaryDistance ParseBinaryDistance(const std::string& name, const std::string& field);

// The distance between two binary rows of `cols` bytes.
uint32_t HammingDistance(const uint8_t* a, const uint8_t* b, int cols);
uint32_t ByteL1Distance(const uint8_t* a, const uint8_t* b, int cols);
inline uint32_t BinaryRowDistance(BinaryDistance distance, const uint8_t* a, const uint8_t* b,
                                  int cols) {
  return distance == BinaryDistance::kByteL1 ? ByteL1Distance(a, b, cols)
                                             : HammingDistance(a, b, cols);
}

}  // namespace duskmap
