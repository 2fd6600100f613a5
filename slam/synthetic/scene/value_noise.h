// Smooth value noise, the one primitive that the procedural textures
// (textures.h) and the materials' relief (relief.h) both draw from; shared
// here so that neither includes the other.
#pragma once

#include <opencv2/core.hpp>

namespace duskmap {

// Smooth value noise in [-1, 1]: a coarse random grid of one cell per
// `cell_texels` texels, upsampled bicubically.
cv::Mat ValueNoise(cv::Size size, double cell_texels, cv::RNG& rng);

}  // namespace duskmap
