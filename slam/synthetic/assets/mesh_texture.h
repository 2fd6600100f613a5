// Texture images of meshes: 8-bit sRGB files decoded to the renderer's
// linear BGR floats, with the image's declared size checked before decoding.
#pragma once

#include <cstdint>
#include <string>

#include <opencv2/core.hpp>

namespace duskmap {

// The sRGB transfer function inverted (IEC 61966-2-1): linear value of an
// sRGB-encoded value in [0, 1].
float SrgbToLinear(float srgb);

// Decodes an image file's bytes (PNG, JPEG or what else OpenCV reads; EXIF
// orientation ignored, alpha dropped, grey expanded) to CV_32FC3 linear BGR
// in [0, 1]. Throws InputError "<source>: <problem>" when its header
// declares more than `max_pixels` pixels (checked before decoding,
// io/image_header.h), or it cannot be decoded.
cv::Mat DecodeSrgbTexture(const std::string& bytes, const std::string& source, int64_t max_pixels);

}  // namespace duskmap
