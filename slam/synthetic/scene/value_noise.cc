#include "slam/synthetic/scene/value_noise.h"

#include <algorithm>

#include <opencv2/imgproc.hpp>

namespace duskmap {

cv::Mat ValueNoise(cv::Size size, double cell_texels, cv::RNG& rng) {
  const int gw = std::max(2, static_cast<int>(size.width / cell_texels) + 2);
  const int gh = std::max(2, static_cast<int>(size.height / cell_texels) + 2);
  cv::Mat grid(gh, gw, CV_32F);
  rng.fill(grid, cv::RNG::UNIFORM, -1.0, 1.0);
  cv::Mat noise;
  cv::resize(grid, noise, size, 0, 0, cv::INTER_CUBIC);
  return noise;
}

}  // namespace duskmap
