// RTAB-Map's RVL depth blobs: Wilson's "Fast Lossless Depth Image Compression"
// (SIGCHI 2017), behind RTAB-Map's 16-byte header.
//   offset 0: "DEPTHRVL"; 8: uint32 width; 12: uint32 height (little-endian);
//   16: payload, 32-bit little-endian words of 8 nibbles, first nibble in
//   bits 31..28. The payload is a sequence of (zero-run length, non-zero run
//   length, zig-zag deltas of the non-zero pixels) as variable-length
//   integers of 3-bit groups, least significant group first, bit 3 = "more".
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace duskmap {

inline constexpr int64_t kMaxRvlPixels = int64_t{1} << 26;  // 64 Mpixels

// Whether the blob starts with the "DEPTHRVL" magic.
bool IsRvlBlob(const uint8_t* data, size_t size);

// Decodes to CV_16UC1 (millimetres in RTAB-Map). Throws InputError
// "<where>: RVL ..." on a bad header, more than kMaxRvlPixels, a truncated
// payload or a run that overflows the image.
cv::Mat DecodeRvlBlob(const uint8_t* data, size_t size, const std::string& where);

// Encodes a CV_16UC1 image exactly as RTAB-Map does (byte-identical blobs).
std::vector<uint8_t> EncodeRvlBlob(const cv::Mat& depth_u16);

}  // namespace duskmap
