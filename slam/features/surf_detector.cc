// Fast-Hessian detector and orientation assignment of SURF.
#include <algorithm>
#include <array>
#include <cmath>

#include <opencv2/core.hpp>

#include "slam/core/check.h"
#include "slam/features/surf.h"

namespace duskmap {
namespace {

constexpr float kPi = 3.14159265358979f;

// Side of the box filter of layer `layer` in octave `octave` (9, 15, 21, 27;
// 15, 27, 39, 51; ...).
int FilterSize(int octave, int layer) { return 3 * ((2 << octave) * (layer + 1) + 1); }

// Corner offsets (into the integral table, relative to the filter's top-left
// corner) and weights of the boxes of the three second-derivative filters.
struct BoxFilter {
  struct Box {
    std::array<int, 4> corner;  // (y0,x0), (y0,x1), (y1,x0), (y1,x1)
    float weight;
  };
  std::array<Box, 2> dxx, dyy;
  std::array<Box, 4> dxy;
  int size = 0;
  // Each response is a difference of box means (sum / box area), as in
  // OpenCV's SURF, so that hessian_threshold keeps the reference's scale
  // (the paper's 100 is a threshold on OpenCV's responses).
  float inv_lobe_area_dd = 0.0f;  // dxx, dyy lobes: lobe x (2 lobe - 1)
  float inv_lobe_area_dxy = 0.0f;  // dxy quadrants: lobe x lobe
};

BoxFilter::Box MakeBox(int x0, int y0, int x1, int y1, float weight, int stride) {
  return {{y0 * stride + x0, y0 * stride + x1, y1 * stride + x0, y1 * stride + x1}, weight};
}

BoxFilter MakeBoxFilter(int size, int stride) {
  const int lobe = size / 3;
  const int half = size / 2;
  const int band0 = (lobe + 1) / 2, band1 = band0 + 2 * lobe - 1;
  BoxFilter f;
  f.size = size;
  f.inv_lobe_area_dd = 1.0f / static_cast<float>(lobe * (2 * lobe - 1));
  f.inv_lobe_area_dxy = 1.0f / static_cast<float>(lobe * lobe);
  // Dyy: +1 over three stacked lobes, -3 over the middle one (net +1 -2 +1).
  f.dyy = {MakeBox(band0, 0, band1, size, 1.0f, stride),
           MakeBox(band0, lobe, band1, 2 * lobe, -3.0f, stride)};
  f.dxx = {MakeBox(0, band0, size, band1, 1.0f, stride),
           MakeBox(lobe, band0, 2 * lobe, band1, -3.0f, stride)};
  f.dxy = {MakeBox(half - lobe, half - lobe, half, half, 1.0f, stride),
           MakeBox(half + 1, half - lobe, half + 1 + lobe, half, -1.0f, stride),
           MakeBox(half - lobe, half + 1, half, half + 1 + lobe, -1.0f, stride),
           MakeBox(half + 1, half + 1, half + 1 + lobe, half + 1 + lobe, 1.0f, stride)};
  return f;
}

template <size_t N>
float ApplyBoxes(const uint32_t* origin, const std::array<BoxFilter::Box, N>& boxes) {
  float sum = 0.0f;
  for (const auto& b : boxes) {
    const uint32_t s = origin[b.corner[3]] - origin[b.corner[1]] - origin[b.corner[2]] +
                       origin[b.corner[0]];
    sum += b.weight * static_cast<float>(static_cast<int32_t>(s));
  }
  return sum;
}

// Determinant-of-Hessian map of one layer on the octave's sampling grid;
// samples whose filter does not fit in the image are 0.
void ComputeResponseLayer(const IntegralImage& integral, int size, int step, int cols, int rows,
                          float* out) {
  const BoxFilter f = MakeBoxFilter(size, integral.stride());
  const int half = size / 2;
  std::fill(out, out + static_cast<size_t>(cols) * rows, 0.0f);
  const int i0 = (half + step - 1) / step;
  const int j0 = i0;
  const int i1 = std::min(cols, (integral.width() - 1 - half) / step + 1);
  const int j1 = std::min(rows, (integral.height() - 1 - half) / step + 1);
  for (int j = j0; j < j1; ++j) {
    const int y0 = j * step - half;
    const uint32_t* row_origin = integral.data() + static_cast<size_t>(y0) * integral.stride();
    float* out_row = out + static_cast<size_t>(j) * cols;
    for (int i = i0; i < i1; ++i) {
      const uint32_t* origin = row_origin + (i * step - half);
      const float dxx = ApplyBoxes(origin, f.dxx) * f.inv_lobe_area_dd;
      const float dyy = ApplyBoxes(origin, f.dyy) * f.inv_lobe_area_dd;
      const float dxy = ApplyBoxes(origin, f.dxy) * f.inv_lobe_area_dxy;
      out_row[i] = dxx * dyy - 0.81f * dxy * dxy;
    }
  }
}

struct Octave {
  int step = 1, cols = 0, rows = 0;
  std::vector<int> sizes;
  std::vector<std::vector<float>> layers;
  float At(int layer, int i, int j) const {
    return layers[layer][static_cast<size_t>(j) * cols + i];
  }
};

bool IsLocalMaximum(const Octave& o, int l, int i, int j, float v) {
  for (int dl = -1; dl <= 1; ++dl) {
    for (int dj = -1; dj <= 1; ++dj) {
      for (int di = -1; di <= 1; ++di) {
        if (dl == 0 && dj == 0 && di == 0) continue;
        if (o.At(l + dl, i + di, j + dj) >= v) return false;
      }
    }
  }
  return true;
}

// Quadratic interpolation in (x, y, layer); false when the offset leaves the cell.
bool Interpolate(const Octave& o, int l, int i, int j, cv::KeyPoint* kp) {
  const float v = o.At(l, i, j);
  const float gx = 0.5f * (o.At(l, i + 1, j) - o.At(l, i - 1, j));
  const float gy = 0.5f * (o.At(l, i, j + 1) - o.At(l, i, j - 1));
  const float gs = 0.5f * (o.At(l + 1, i, j) - o.At(l - 1, i, j));
  const float hxx = o.At(l, i + 1, j) + o.At(l, i - 1, j) - 2 * v;
  const float hyy = o.At(l, i, j + 1) + o.At(l, i, j - 1) - 2 * v;
  const float hss = o.At(l + 1, i, j) + o.At(l - 1, i, j) - 2 * v;
  const float hxy = 0.25f * (o.At(l, i + 1, j + 1) - o.At(l, i - 1, j + 1) -
                             o.At(l, i + 1, j - 1) + o.At(l, i - 1, j - 1));
  const float hxs = 0.25f * (o.At(l + 1, i + 1, j) - o.At(l + 1, i - 1, j) -
                             o.At(l - 1, i + 1, j) + o.At(l - 1, i - 1, j));
  const float hys = 0.25f * (o.At(l + 1, i, j + 1) - o.At(l + 1, i, j - 1) -
                             o.At(l - 1, i, j + 1) + o.At(l - 1, i, j - 1));
  const cv::Matx33f h(hxx, hxy, hxs, hxy, hyy, hys, hxs, hys, hss);
  cv::Vec3f offset;
  if (!cv::solve(h, cv::Vec3f(-gx, -gy, -gs), offset, cv::DECOMP_LU)) return false;
  if (std::abs(offset[0]) > 1.0f || std::abs(offset[1]) > 1.0f || std::abs(offset[2]) > 1.0f) {
    return false;
  }
  const float size_step = static_cast<float>(o.sizes[l + 1] - o.sizes[l]);
  kp->pt = cv::Point2f((i + offset[0]) * o.step, (j + offset[1]) * o.step);
  kp->size = o.sizes[l] + offset[2] * size_step;
  kp->response = v;
  return true;
}

void FindExtrema(const Octave& o, int octave_index, int image_w, int image_h, double threshold,
                 std::vector<cv::KeyPoint>* out) {
  const int layers = static_cast<int>(o.layers.size());
  for (int l = 1; l + 1 < layers; ++l) {
    const int margin = (o.sizes[l + 1] / 2 + o.step - 1) / o.step + 1;
    for (int j = margin; j + margin <= o.rows - 1; ++j) {
      for (int i = margin; i + margin <= o.cols - 1; ++i) {
        const float v = o.At(l, i, j);
        if (v <= threshold || !IsLocalMaximum(o, l, i, j, v)) continue;
        cv::KeyPoint kp;
        if (!Interpolate(o, l, i, j, &kp)) continue;
        if (kp.pt.x < 0 || kp.pt.y < 0 || kp.pt.x > image_w - 1 || kp.pt.y > image_h - 1) continue;
        kp.octave = octave_index;
        kp.class_id = l;
        out->push_back(kp);
      }
    }
  }
}

// Dominant orientation (radians) from Haar responses within radius 6s,
// Gaussian-weighted (sigma 2s), summed in a sliding window of pi/3.
float DominantOrientation(const IntegralImage& integral, const cv::KeyPoint& kp) {
  struct Sample {
    float angle, dx, dy;
  };
  static const auto kOffsets = [] {
    std::vector<std::array<float, 3>> offsets;  // i, j, weight
    for (int j = -6; j <= 6; ++j) {
      for (int i = -6; i <= 6; ++i) {
        if (i * i + j * j >= 36) continue;
        offsets.push_back({float(i), float(j), std::exp(-(i * i + j * j) / (2.0f * 2.0f * 2.0f))});
      }
    }
    return offsets;
  }();
  std::array<Sample, 128> samples;
  SLAM_CHECK(kOffsets.size() <= samples.size());
  const float s = 1.2f * kp.size / 9.0f;
  const int half = std::max(1, static_cast<int>(std::lround(2.0f * s)));
  size_t n = 0;
  for (const auto& off : kOffsets) {
    const int x = static_cast<int>(std::lround(kp.pt.x + off[0] * s));
    const int y = static_cast<int>(std::lround(kp.pt.y + off[1] * s));
    float dx, dy;
    integral.Haar(x, y, half, &dx, &dy);
    if (dx == 0.0f && dy == 0.0f) continue;
    dx *= off[2];
    dy *= off[2];
    samples[n++] = {std::atan2(dy, dx), dx, dy};
  }
  if (n == 0) return 0.0f;
  std::sort(samples.begin(), samples.begin() + n,
            [](const Sample& a, const Sample& b) { return a.angle < b.angle; });
  constexpr float kWindow = kPi / 3.0f;
  float best = -1.0f, best_x = 0.0f, best_y = 0.0f, sum_x = 0.0f, sum_y = 0.0f;
  size_t end = 0;  // window is [k, end) over the samples repeated once (+2 pi)
  auto angle_at = [&](size_t idx) {
    return idx < n ? samples[idx].angle : samples[idx - n].angle + 2.0f * kPi;
  };
  for (size_t k = 0; k < n; ++k) {
    if (end < k) end = k;
    while (end < k + n && angle_at(end) < samples[k].angle + kWindow) {
      sum_x += samples[end % n].dx;
      sum_y += samples[end % n].dy;
      ++end;
    }
    const float norm = sum_x * sum_x + sum_y * sum_y;
    if (norm > best) {
      best = norm;
      best_x = sum_x;
      best_y = sum_y;
    }
    if (end > k) {
      sum_x -= samples[k].dx;
      sum_y -= samples[k].dy;
    }
  }
  return std::atan2(best_y, best_x);
}

}  // namespace

std::vector<cv::KeyPoint> DetectSurfKeypoints(const IntegralImage& integral,
                                              const SurfOptions& options, int max_features) {
  options.Check();
  std::vector<cv::KeyPoint> keypoints;
  const int layers = options.octave_layers + 2;
  for (int octave = 0; octave < options.octaves; ++octave) {
    Octave o;
    o.step = 1 << octave;
    o.cols = (integral.width() + o.step - 1) / o.step;
    o.rows = (integral.height() + o.step - 1) / o.step;
    for (int l = 0; l < layers; ++l) o.sizes.push_back(FilterSize(octave, l));
    if (o.sizes.back() + 2 * o.step >= std::min(integral.width(), integral.height())) break;
    o.layers.resize(layers);
    for (int l = 0; l < layers; ++l) {
      o.layers[l].resize(static_cast<size_t>(o.cols) * o.rows);
      ComputeResponseLayer(integral, o.sizes[l], o.step, o.cols, o.rows, o.layers[l].data());
    }
    FindExtrema(o, octave, integral.width(), integral.height(), options.hessian_threshold,
                &keypoints);
  }
  std::stable_sort(keypoints.begin(), keypoints.end(),
                   [](const cv::KeyPoint& a, const cv::KeyPoint& b) {
                     return a.response > b.response;
                   });
  if (keypoints.size() > static_cast<size_t>(max_features)) keypoints.resize(max_features);
  for (cv::KeyPoint& kp : keypoints) {
    float angle_deg = 0.0f;
    if (!options.upright) {
      angle_deg = DominantOrientation(integral, kp) * 180.0f / kPi;
      if (angle_deg < 0.0f) angle_deg += 360.0f;
      if (angle_deg >= 360.0f) angle_deg -= 360.0f;
    }
    kp.angle = angle_deg;
  }
  return keypoints;
}

}  // namespace duskmap
