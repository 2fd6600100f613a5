#include "slam/features/eval_image.h"

#include <opencv2/imgcodecs.hpp>

#include "slam/core/check.h"

namespace duskmap {

cv::Mat ReadEvalImage(const std::string& path) {
  cv::Mat image = cv::imread(path, cv::IMREAD_COLOR);
  SLAM_THROW_IF_NOT(InputError, !image.empty()) << path << ": cannot read image";
  return image;
}

}  // namespace duskmap
