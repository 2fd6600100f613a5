// Identifiers of visual words and the distance used to compare descriptors.
#pragma once

#include <cstddef>
#include <cstdint>

#include "slam/features/binary_distance.h"
#include "slam/features/descriptor_quantization.h"
#include "slam/features/frame_features.h"

namespace duskmap {

// Positive, increasing in creation order; never reused (as in the reference).
using WordId = int32_t;
// A descriptor that was not quantized (bad frame, beyond Kp/MaxFeatures, or
// unmatched during a lookup-only quantization).
constexpr WordId kNoWord = -1;

// Distance between two descriptors as the vocabulary compares them: squared
// L2 for float rows (what FLANN returns); for binary rows Hamming or the L1
// of the byte values (`binary`, binary_distance.h). `cols` is the number of
// elements (floats or bytes) of one row.
float DescriptorDistance(DescriptorKind kind, const uint8_t* a, const uint8_t* b, int cols,
                         BinaryDistance binary = BinaryDistance::kHamming);
// The same, but may stop early and return any value >= `bound` once the
// distance is known to reach it (the exact distance when it is below).
float DescriptorDistanceBounded(DescriptorKind kind, const uint8_t* a, const uint8_t* b, int cols,
                                float bound, BinaryDistance binary = BinaryDistance::kHamming);

// How the vocabulary stores a word's descriptor. Queries are always rows as
// extracted (floats or bytes); only the stored side changes.
enum class WordRowFormat {
  kFloat32,     // `cols` floats, as extracted
  kQuantized8,  // a RowScale (offset, step: 8 bytes), then `cols` 8-bit codes
                // (features/descriptor_quantization.h): a quarter of the bytes
  kBinary,      // `cols` bytes, as extracted
};

WordRowFormat WordRowFormatFor(DescriptorKind kind, DescriptorStorage float_storage);
size_t WordRowBytes(WordRowFormat format, int cols);
// Bytes of one extracted (query) row: 4 x cols for float formats.
size_t QueryRowBytes(WordRowFormat format, int cols);
// Extracted row -> stored row. False (stored row unspecified) when a float
// row to quantize holds a non-finite value.
bool EncodeWordRow(WordRowFormat format, const uint8_t* descriptor, int cols, uint8_t* stored);
// A kQuantized8 stored row from 8-bit codes already made with `scale` (the
// form node descriptors keep them in): the scale, then the `cols` codes.
void StoreQuantizedWordRow(const uint8_t* codes, RowScale scale, int cols, uint8_t* stored);
// Stored row -> extracted form (the quantized values for kQuantized8).
void DecodeWordRow(WordRowFormat format, const uint8_t* stored, int cols, uint8_t* descriptor);
// Element `dim` of a stored row as a float: for kBinary one bit (Hamming,
// the reference's byte-to-bits expansion) or one byte value (byte_l1, its
// Kp/ByteToFloat).
float WordRowValue(WordRowFormat format, const uint8_t* stored, int dim,
                   BinaryDistance binary = BinaryDistance::kHamming);
// The dimensions a KD-tree splits rows on: the bits of a binary row compared
// by Hamming, otherwise the row's elements.
int WordRowDims(WordRowFormat format, int cols, BinaryDistance binary);
// Distance between an extracted query row and a stored word row, as
// DescriptorDistance(Bounded) computes it between two extracted rows (for
// kQuantized8, against the quantized values).
float WordDistance(WordRowFormat format, const uint8_t* query, const uint8_t* stored, int cols,
                   BinaryDistance binary = BinaryDistance::kHamming);
float WordDistanceBounded(WordRowFormat format, const uint8_t* query, const uint8_t* stored,
                          int cols, float bound, BinaryDistance binary = BinaryDistance::kHamming);

namespace detail {
// WordDistance of a kQuantized8 row computed with the SSE2 code path, which
// machines without AVX2 run (for the test that both paths agree bit for bit).
float QuantizedWordDistanceBaselineSimd(const uint8_t* query, const uint8_t* stored, int cols);
}  // namespace detail

}  // namespace duskmap
