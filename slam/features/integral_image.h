// Integral image of an 8-bit image for O(1) box sums (SURF, FREAK).
// Stored as uint32 with wrap-around: the sum over any box is at most
// 255 * area, which fits in 32 bits, and modular arithmetic makes the
// four-corner difference exact even when the running totals overflow.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

namespace duskmap {

class IntegralImage {
 public:
  explicit IntegralImage(const cv::Mat& gray8);

  int width() const { return width_; }
  int height() const { return height_; }
  // Row stride of the table (width + 1 entries).
  int stride() const { return width_ + 1; }
  const uint32_t* data() const { return table_.data(); }

  // Sum over columns [x0, x1) and rows [y0, y1); the box must lie inside.
  int BoxSum(int x0, int y0, int x1, int y1) const {
    const uint32_t* t = table_.data();
    const int s = stride();
    return static_cast<int>(t[y1 * s + x1] - t[y0 * s + x1] - t[y1 * s + x0] + t[y0 * s + x0]);
  }
  // Same, with the box clipped to the image (0 when nothing is left).
  int BoxSumClipped(int x0, int y0, int x1, int y1) const {
    x0 = std::clamp(x0, 0, width_);
    x1 = std::clamp(x1, 0, width_);
    y0 = std::clamp(y0, 0, height_);
    y1 = std::clamp(y1, 0, height_);
    if (x1 <= x0 || y1 <= y0) return 0;
    return BoxSum(x0, y0, x1, y1);
  }
  // Haar wavelet responses of side 2*half centred on (x, y): right minus left
  // half (dx) and bottom minus top half (dy), clipped to the image.
  void Haar(int x, int y, int half, float* dx, float* dy) const {
    if (x - half >= 0 && y - half >= 0 && x + half <= width_ && y + half <= height_) {
      *dx = static_cast<float>(BoxSum(x, y - half, x + half, y + half) -
                               BoxSum(x - half, y - half, x, y + half));
      *dy = static_cast<float>(BoxSum(x - half, y, x + half, y + half) -
                               BoxSum(x - half, y - half, x + half, y));
      return;
    }
    *dx = static_cast<float>(BoxSumClipped(x, y - half, x + half, y + half) -
                             BoxSumClipped(x - half, y - half, x, y + half));
    *dy = static_cast<float>(BoxSumClipped(x - half, y, x + half, y + half) -
                             BoxSumClipped(x - half, y - half, x + half, y));
  }

 private:
  int width_ = 0;
  int height_ = 0;
  std::vector<uint32_t> table_;
};

}  // namespace duskmap
