// A fixed camera's sequence for the tests of `features eval`'s static
// layout: one textured scene, the same view in every image, the light
// dimming from day to dusk (gain and offset per image, a little sensor
// noise), written as img1..imgN.png (or under the names given).
#pragma once

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "tests/features/test_images.h"

namespace duskmap::testing {

// The gain of image k (0-based) of the static scene: 1, 0.7, 0.49, ...
inline double StaticSceneGain(int k) { return std::pow(0.7, k); }

// Writes `count` images of the scene into `dir`; names[k] replaces
// "img<k+1>.png" when given. Returns the paths written.
inline std::vector<std::string> WriteStaticScene(const std::filesystem::path& dir, int count,
                                                 const std::vector<std::string>& names = {}) {
  std::filesystem::create_directories(dir);
  const cv::Mat scene = TexturedImage(320, 240, 29);
  std::vector<std::string> paths;
  for (int k = 0; k < count; ++k) {
    cv::Mat image;
    scene.convertTo(image, CV_8U, StaticSceneGain(k), 8.0);
    image = AddNoise(image, 1.0, 100 + k);
    const std::string name = k < static_cast<int>(names.size()) ? names[k] : "img" + std::to_string(k + 1) + ".png";
    paths.push_back((dir / name).string());
    cv::imwrite(paths.back(), image);
  }
  return paths;
}

}  // namespace duskmap::testing
