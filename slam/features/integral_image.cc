#include "slam/features/integral_image.h"

#include "slam/core/check.h"

namespace duskmap {

IntegralImage::IntegralImage(const cv::Mat& gray8) : width_(gray8.cols), height_(gray8.rows) {
  SLAM_CHECK(gray8.type() == CV_8UC1);
  const int s = stride();
  table_.assign(static_cast<size_t>(s) * (height_ + 1), 0u);
  for (int y = 0; y < height_; ++y) {
    const uint8_t* row = gray8.ptr<uint8_t>(y);
    const uint32_t* above = table_.data() + static_cast<size_t>(y) * s;
    uint32_t* out = table_.data() + static_cast<size_t>(y + 1) * s;
    uint32_t running = 0;
    for (int x = 0; x < width_; ++x) {
      running += row[x];
      out[x + 1] = above[x + 1] + running;
    }
  }
}

}  // namespace duskmap
