// Decoding of RTAB-Map image blobs (database `Data.image` / `Data.depth`, and
// the image release's JPEG / PNG files), sniffed by their magic bytes:
// JPEG (FF D8), PNG (89 'PNG'), RVL ("DEPTHRVL").
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include <opencv2/core.hpp>

namespace duskmap {

enum class BlobCodec { kJpeg, kPng, kRvl, kUnknown };

BlobCodec SniffBlobCodec(const uint8_t* data, size_t size);

// A colour image (JPEG or PNG, 8-bit grey or colour) as CV_8UC3 BGR. Throws
// InputError "<where>: <problem>" when the blob is not an image, is truncated
// or does not decode, or is not 8-bit.
cv::Mat DecodeColorBlob(const uint8_t* data, size_t size, const std::string& where);

// A depth image as CV_32FC1 metres (0 = invalid): RVL or 16-bit PNG in
// millimetres, or RTAB-Map's float depth packed in an 8-bit 4-channel PNG.
// Throws InputError naming `where` for anything else ("depth of unexpected
// type") or a blob that does not decode.
cv::Mat DecodeDepthBlob(const uint8_t* data, size_t size, const std::string& where);

// CV_16UC1 millimetres to CV_32FC1 metres.
cv::Mat DepthMillimetresToMetres(const cv::Mat& depth_mm);

}  // namespace duskmap
