#include "slam/synthetic/raster/mip_texture.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "slam/core/check.h"

namespace duskmap {

namespace {

// The area-weighted box filter from n texels to m = max(1, n / 2): texel j
// of the result covers source units [j n / m, (j + 1) n / m). In units of
// 1 / m, source texel i covers [i m, (i + 1) m) and result texel j covers
// [j n, (j + 1) n), so the overlaps, and the weights overlap / n, are exact.
struct Tap {
  int source = 0;
  float weight = 0.0f;
};

std::vector<std::vector<Tap>> BoxTaps(int n, int m) {
  std::vector<std::vector<Tap>> taps(static_cast<size_t>(m));
  for (int j = 0; j < m; ++j) {
    const int64_t lo = static_cast<int64_t>(j) * n, hi = lo + n;
    for (int i = static_cast<int>(lo / m); i < n && static_cast<int64_t>(i) * m < hi; ++i) {
      const int64_t overlap = std::min<int64_t>(hi, static_cast<int64_t>(i + 1) * m) -
                              std::max<int64_t>(lo, static_cast<int64_t>(i) * m);
      if (overlap > 0) taps[j].push_back({i, static_cast<float>(static_cast<double>(overlap) / n)});
    }
  }
  return taps;
}

cv::Mat HalveColumns(const cv::Mat& source) {
  const int m = std::max(1, source.cols / 2);
  const std::vector<std::vector<Tap>> taps = BoxTaps(source.cols, m);
  cv::Mat out(source.rows, m, CV_32FC3);
  for (int row = 0; row < source.rows; ++row) {
    const cv::Vec3f* in = source.ptr<cv::Vec3f>(row);
    cv::Vec3f* result = out.ptr<cv::Vec3f>(row);
    for (int j = 0; j < m; ++j) {
      cv::Vec3f sum(0.0f, 0.0f, 0.0f);
      for (const Tap& t : taps[j]) sum += in[t.source] * t.weight;
      result[j] = sum;
    }
  }
  return out;
}

cv::Mat HalveRows(const cv::Mat& source) {
  const int m = std::max(1, source.rows / 2);
  const std::vector<std::vector<Tap>> taps = BoxTaps(source.rows, m);
  cv::Mat out(m, source.cols, CV_32FC3, cv::Scalar::all(0.0));
  for (int j = 0; j < m; ++j) {
    cv::Vec3f* result = out.ptr<cv::Vec3f>(j);
    for (const Tap& t : taps[j]) {
      const cv::Vec3f* in = source.ptr<cv::Vec3f>(t.source);
      for (int col = 0; col < source.cols; ++col) result[col] += in[col] * t.weight;
    }
  }
  return out;
}

// Wraps a texture coordinate into [0, 1]; non-finite values read as 0.
double Wrap(double t) {
  if (!std::isfinite(t)) return 0.0;
  return t - std::floor(t);
}

// The two texels around continuous texel coordinate x (texel centres at
// integers) of a row of n texels, wrapped, and the weight of the second.
void Neighbours(double x, int n, int* i0, int* i1, float* fraction) {
  const double x0 = std::floor(x);
  *fraction = static_cast<float>(x - x0);
  *i0 = static_cast<int>(x0);
  if (*i0 < 0) *i0 += n;
  if (*i0 >= n) *i0 -= n;
  *i1 = *i0 + 1 == n ? 0 : *i0 + 1;
}

}  // namespace

MipTexture::MipTexture(const cv::Mat& image_bgr) {
  SLAM_THROW_IF_NOT(InputError, !image_bgr.empty() && image_bgr.type() == CV_32FC3)
      << "MipTexture: the image must be a non-empty CV_32FC3, got " << image_bgr.cols << "x"
      << image_bgr.rows << " of type " << image_bgr.type();
  levels_.push_back(image_bgr);
  while (levels_.back().cols > 1 || levels_.back().rows > 1) {
    levels_.push_back(HalveRows(HalveColumns(levels_.back())));
  }
}

cv::Vec3f MipTexture::SampleLevel(int level, double u, double v) const {
  const cv::Mat& image = levels_[static_cast<size_t>(level)];
  const double x = Wrap(u) * image.cols - 0.5;
  const double y = (1.0 - Wrap(v)) * image.rows - 0.5;  // v up, row 0 at the top
  int x0, x1, y0, y1;
  float fx, fy;
  Neighbours(x, image.cols, &x0, &x1, &fx);
  Neighbours(y, image.rows, &y0, &y1, &fy);
  const cv::Vec3f* r0 = image.ptr<cv::Vec3f>(y0);
  const cv::Vec3f* r1 = image.ptr<cv::Vec3f>(y1);
  return (r0[x0] * (1.0f - fx) + r0[x1] * fx) * (1.0f - fy) + (r1[x0] * (1.0f - fx) + r1[x1] * fx) * fy;
}

cv::Vec3f MipTexture::Sample(double u, double v, double footprint_texels) const {
  SLAM_CHECK(!empty());
  const int last = num_levels() - 1;
  const double lod = std::min(footprint_texels > 1.0 ? std::log2(footprint_texels) : 0.0,
                              static_cast<double>(last));
  const int level = static_cast<int>(lod);
  const float blend = static_cast<float>(lod - level);
  const cv::Vec3f fine = SampleLevel(level, u, v);
  if (blend <= 0.0f) return fine;
  return fine * (1.0f - blend) + SampleLevel(level + 1, u, v) * blend;
}

double FootprintTexels(double du_dx, double dv_dx, double du_dy, double dv_dy, int width, int height) {
  const double ax = du_dx * width, ay = dv_dx * height;
  const double bx = du_dy * width, by = dv_dy * height;
  return std::sqrt(std::max(ax * ax + ay * ay, bx * bx + by * by));
}

}  // namespace duskmap
