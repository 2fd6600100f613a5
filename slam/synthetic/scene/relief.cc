#include "slam/synthetic/scene/relief.h"

#include <algorithm>

#include <opencv2/imgproc.hpp>

#include "slam/core/check.h"
#include "slam/synthetic/scene/value_noise.h"

namespace duskmap {

ReliefCanvas::ReliefCanvas(cv::Size size, double texel_m)
    : height_m_(size, CV_32F, cv::Scalar(0)), texel_m_(texel_m) {
  SLAM_CHECK(texel_m > 0.0);
}

void ReliefCanvas::AddNoise(double amplitude_m, double cell_m, cv::RNG& rng) {
  if (!enabled()) return;
  const cv::Mat noise = ValueNoise(height_m_.size(), std::max(1.0, cell_m / texel_m_), rng);
  cv::scaleAdd(noise, amplitude_m, height_m_, height_m_);
}

void ReliefCanvas::AddRect(const cv::Rect& texels, double height_m) {
  if (!enabled()) return;
  const cv::Rect clipped = texels & cv::Rect(0, 0, height_m_.cols, height_m_.rows);
  if (clipped.area() > 0) height_m_(clipped) += height_m;
}

void ReliefCanvas::GrooveColumn(int column, double depth_m) {
  if (!enabled()) return;
  AddRect(cv::Rect(column, 0, 1, height_m_.rows), -depth_m);
  AddRect(cv::Rect(column - 1, 0, 1, height_m_.rows), -0.4 * depth_m);
  AddRect(cv::Rect(column + 1, 0, 1, height_m_.rows), -0.4 * depth_m);
}

void ReliefCanvas::GrooveRow(int row, double depth_m) {
  if (!enabled()) return;
  AddRect(cv::Rect(0, row, height_m_.cols, 1), -depth_m);
  AddRect(cv::Rect(0, row - 1, height_m_.cols, 1), -0.4 * depth_m);
  AddRect(cv::Rect(0, row + 1, height_m_.cols, 1), -0.4 * depth_m);
}

cv::Mat ReliefSlopes(const cv::Mat& height_m, double texel_x_m, double texel_y_m) {
  SLAM_CHECK(height_m.type() == CV_32F && texel_x_m > 0.0 && texel_y_m > 0.0);
  cv::Mat slopes(height_m.size(), CV_32FC2);
  const int w = height_m.cols, h = height_m.rows;
  for (int r = 0; r < h; ++r) {
    const float* row = height_m.ptr<float>(r);
    const float* up = height_m.ptr<float>(std::max(r - 1, 0));
    const float* down = height_m.ptr<float>(std::min(r + 1, h - 1));
    const float dy = static_cast<float>(((r > 0 ? 1 : 0) + (r + 1 < h ? 1 : 0)) * texel_y_m);
    cv::Vec2f* out = slopes.ptr<cv::Vec2f>(r);
    for (int c = 0; c < w; ++c) {
      const int left = std::max(c - 1, 0), right = std::min(c + 1, w - 1);
      const float dx = static_cast<float>((right - left) * texel_x_m);
      out[c][0] = dx > 0.0f ? (row[right] - row[left]) / dx : 0.0f;
      out[c][1] = dy > 0.0f ? (down[c] - up[c]) / dy : 0.0f;
    }
  }
  return slopes;
}

}  // namespace duskmap
