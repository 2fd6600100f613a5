#include "slam/features/eval/eval_image.h"

#include <opencv2/imgcodecs.hpp>

#include "slam/core/check.h"
#include "slam/io/image_header.h"

namespace duskmap {

cv::Mat ReadEvalImage(const std::string& path) {
  // The dataset readers' checks: a header declaring 100000x100000 pixels is
  // refused before OpenCV allocates them (it failed an assertion), a cut
  // JPEG before it decodes grey, a FIFO before it blocks.
  CheckImageFileBeforeDecoding(path);
  cv::Mat image = cv::imread(path, cv::IMREAD_COLOR);
  SLAM_THROW_IF_NOT(InputError, !image.empty()) << path << ": cannot read image";
  return image;
}

}  // namespace duskmap
