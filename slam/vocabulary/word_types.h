// Identifiers of visual words and the distance used to compare descriptors.
#pragma once

#include <cstdint>

#include "slam/features/frame_features.h"

namespace duskmap {

// Positive, increasing in creation order; never reused (as in the reference).
using WordId = int32_t;
// A descriptor that was not quantized (bad frame, beyond Kp/MaxFeatures, or
// unmatched during a lookup-only quantization).
constexpr WordId kNoWord = -1;

// Distance between two descriptors as the vocabulary compares them: squared
// L2 for float rows (what FLANN returns), Hamming for binary rows.
// `cols` is the number of elements (floats or bytes) of one row.
float DescriptorDistance(DescriptorKind kind, const uint8_t* a, const uint8_t* b, int cols);
// The same, but may stop early and return any value >= `bound` once the
// distance is known to reach it (the exact distance when it is below).
float DescriptorDistanceBounded(DescriptorKind kind, const uint8_t* a, const uint8_t* b, int cols,
                                float bound);

}  // namespace duskmap
