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

// Corner offsets (into the integral table, relative to the filter's top-left
// corner) and weights of the boxes of the three second-derivative filters.
struct BoxFilter {
  struct Box {
    std::array<int, 4> corner;  // (y0,x0), (y0,x1), (y1,x0), (y1,x1)
    float weight;               // +-1 or -3 over the box's area in pixels
  };
  std::array<Box, 2> dxx, dyy;
  std::array<Box, 4> dxy;
  int size = 0;
};

// The size-9 filters' boxes (x0, y0, x1, y1, weight), pixel edges: Dxx is
// three 3x5 lobes weighted +1 -2 +1, Dxy four 3x3 quadrants around a centre
// row and column of zeros. Larger filters scale every edge by size / 9,
// rounded, so that lobes keep whole pixels (size 15: 5x9 lobes; 18: 6x10).
// Each lobe's weight is divided by its area: a response is a difference of
// box means, which is the scale on which OpenCV's SURF applies its Hessian
// threshold (the paper's 100).
std::array<int, 4> ScaledEdges(int size, std::array<int, 4> edges9) {
  const float ratio = static_cast<float>(size) / 9.0f;
  std::array<int, 4> e{};
  for (int k = 0; k < 4; ++k) e[k] = static_cast<int>(std::lround(ratio * edges9[k]));
  return e;
}

BoxFilter::Box MakeBox(int size, std::array<int, 4> edges9, float weight, int stride) {
  const auto [x0, y0, x1, y1] = ScaledEdges(size, edges9);
  return {{y0 * stride + x0, y0 * stride + x1, y1 * stride + x0, y1 * stride + x1},
          weight};
}

float BoxArea(int size, std::array<int, 4> edges9) {
  const auto [x0, y0, x1, y1] = ScaledEdges(size, edges9);
  return static_cast<float>((x1 - x0) * (y1 - y0));
}

BoxFilter MakeBoxFilter(int size, int stride) {
  BoxFilter f;
  f.size = size;
  // Dxx: +1 over the three lobes together, -3 over the middle one (net +1 -2
  // +1); the three lobes have equal areas because 3 divides every size.
  const float lobe_dd = BoxArea(size, {3, 2, 6, 7});
  f.dxx = {MakeBox(size, {0, 2, 9, 7}, 1.0f / lobe_dd, stride),
           MakeBox(size, {3, 2, 6, 7}, -3.0f / lobe_dd, stride)};
  f.dyy = {MakeBox(size, {2, 0, 7, 9}, 1.0f / lobe_dd, stride),
           MakeBox(size, {2, 3, 7, 6}, -3.0f / lobe_dd, stride)};
  const float quadrant = BoxArea(size, {1, 1, 4, 4});
  f.dxy = {MakeBox(size, {1, 1, 4, 4}, 1.0f / quadrant, stride),
           MakeBox(size, {5, 1, 8, 4}, -1.0f / quadrant, stride),
           MakeBox(size, {1, 5, 4, 8}, -1.0f / quadrant, stride),
           MakeBox(size, {5, 5, 8, 8}, 1.0f / quadrant, stride)};
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

// Sample i of an octave sampled every `step` pixels sits at pixel coordinate
// i * step + (step - 1) / 2: the centre of a filter whose top-left pixel edge
// is i * step - (size - step) / 2, for every layer of the octave (its sizes
// are multiples of the step with the step's parity).
float SampleCentre(int i, int step) { return i * step + 0.5f * (step - 1); }

// Determinant-of-Hessian map of one layer on the octave's sampling grid;
// samples whose filter does not fit in the image are 0.
void ComputeResponseLayer(const IntegralImage& integral, int size, int step, int cols, int rows,
                          float* out) {
  const BoxFilter f = MakeBoxFilter(size, integral.stride());
  const int offset = (size - step) / 2;  // sample position minus the filter's top-left edge
  std::fill(out, out + static_cast<size_t>(cols) * rows, 0.0f);
  const int first = (offset + step - 1) / step;
  const int i1 = std::min(cols, (integral.width() - size + offset) / step + 1);
  const int j1 = std::min(rows, (integral.height() - size + offset) / step + 1);
  for (int j = first; j < j1; ++j) {
    const int y0 = j * step - offset;
    const uint32_t* row_origin = integral.data() + static_cast<size_t>(y0) * integral.stride();
    float* out_row = out + static_cast<size_t>(j) * cols;
    for (int i = first; i < i1; ++i) {
      const uint32_t* origin = row_origin + (i * step - offset);
      const float dxx = ApplyBoxes(origin, f.dxx);
      const float dyy = ApplyBoxes(origin, f.dyy);
      const float dxy = ApplyBoxes(origin, f.dxy);
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
  if (offset == cv::Vec3f(0.0f, 0.0f, 0.0f)) return false;  // a singular fit, as the reference
  if (std::abs(offset[0]) > 1.0f || std::abs(offset[1]) > 1.0f || std::abs(offset[2]) > 1.0f) {
    return false;
  }
  const float size_step = static_cast<float>(o.sizes[l] - o.sizes[l - 1]);
  kp->pt = cv::Point2f(SampleCentre(i, o.step) + offset[0] * o.step,
                       SampleCentre(j, o.step) + offset[1] * o.step);
  // Whole pixels, as OpenCV's SURF reports the filter side.
  kp->size = static_cast<float>(std::lround(o.sizes[l] + offset[2] * size_step));
  kp->response = v;
  return true;
}

void FindExtrema(const Octave& o, int octave_index, int image_w, int image_h, double threshold,
                 std::vector<cv::KeyPoint>* out) {
  const int layers = static_cast<int>(o.layers.size());
  for (int l = 1; l + 1 < layers; ++l) {
    // Every 3x3x3 neighbour, the layer above's included, has its filter
    // inside the image.
    const int margin = (o.sizes[l + 1] / 2) / o.step + 1;
    for (int j = margin; j < o.rows - margin; ++j) {
      for (int i = margin; i < o.cols - margin; ++i) {
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

// Dominant orientation (radians, image axes) as OpenCV's SURF assigns it:
// Haar responses of side 4s (2 round(2s)) at the grid points i, j of step s
// with i^2 + j^2 <= 36, Gaussian-weighted (sigma 2.5 s); the window of
// +-30 degrees around each multiple of 5 degrees whose summed response is
// longest gives the direction. Samples whose wavelet leaves the image are
// skipped; 0 when none is left.
float DominantOrientation(const IntegralImage& integral, const cv::KeyPoint& kp) {
  constexpr int kRadius = 6;
  constexpr float kSigma = 2.5f;
  constexpr int kSearchStepDeg = 5;
  constexpr int kHalfWindowDeg = 30;
  static const auto kOffsets = [] {
    std::vector<std::array<float, 3>> offsets;  // i, j, weight
    for (int j = -kRadius; j <= kRadius; ++j) {
      for (int i = -kRadius; i <= kRadius; ++i) {
        if (i * i + j * j > kRadius * kRadius) continue;
        offsets.push_back({float(i), float(j), std::exp(-(i * i + j * j) / (2.0f * kSigma * kSigma))});
      }
    }
    return offsets;
  }();
  struct Sample {
    int angle_deg;
    float dx, dy;
  };
  std::array<Sample, 128> samples;
  SLAM_CHECK(kOffsets.size() <= samples.size());
  const float s = 1.2f * kp.size / 9.0f;
  const int half = std::max(1, static_cast<int>(std::lround(2.0f * s)));
  const int side = 2 * half;
  size_t n = 0;
  for (const auto& off : kOffsets) {
    const int x0 = static_cast<int>(std::lround(kp.pt.x + off[0] * s - 0.5f * (side - 1)));
    const int y0 = static_cast<int>(std::lround(kp.pt.y + off[1] * s - 0.5f * (side - 1)));
    if (x0 < 0 || y0 < 0 || x0 + side > integral.width() || y0 + side > integral.height()) continue;
    float dx, dy;
    integral.Haar(x0 + half, y0 + half, half, &dx, &dy);
    dx *= off[2];
    dy *= off[2];
    float angle = std::atan2(dy, dx) * 180.0f / kPi;
    if (angle < 0.0f) angle += 360.0f;
    samples[n++] = {static_cast<int>(std::lround(angle)), dx, dy};
  }
  if (n == 0) return 0.0f;
  float best = 0.0f, best_x = 0.0f, best_y = 0.0f;
  for (int centre = 0; centre < 360; centre += kSearchStepDeg) {
    float sum_x = 0.0f, sum_y = 0.0f;
    for (size_t k = 0; k < n; ++k) {
      const int d = std::abs(samples[k].angle_deg - centre);
      if (d < kHalfWindowDeg || d > 360 - kHalfWindowDeg) {
        sum_x += samples[k].dx;
        sum_y += samples[k].dy;
      }
    }
    const float norm = sum_x * sum_x + sum_y * sum_y;
    if (norm > best) {
      best = norm;
      best_x = sum_x;
      best_y = sum_y;
    }
  }
  return std::atan2(best_y, best_x);
}

}  // namespace

int SurfFilterSide(int octave, int layer) { return (9 + 6 * layer) << octave; }

std::vector<cv::KeyPoint> DetectSurfKeypoints(const IntegralImage& integral,
                                              const SurfOptions& options, int max_features) {
  options.Check();
  std::vector<cv::KeyPoint> keypoints;
  const int layers = options.octave_layers + 2;
  for (int octave = 0; octave < options.octaves; ++octave) {
    Octave o;
    o.step = 1 << octave;
    o.cols = integral.width() / o.step;
    o.rows = integral.height() / o.step;
    for (int l = 0; l < layers; ++l) o.sizes.push_back(SurfFilterSide(octave, l));
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
