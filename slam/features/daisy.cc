#include "slam/features/daisy.h"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

#include "slam/features/integral_image.h"
#include "slam/features/surf.h"

namespace duskmap {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Blur of the grey image before its gradients, and the scale the oriented
// gradient maps are brought to before the rings' smoothing: OpenCV's DAISY
// (the reference's SURF/DAISY runs) smooths the image by 0.5 and the maps by
// sqrt(1.6^2 - 0.5^2).
constexpr double kImageSigma = 0.5;
constexpr double kBaseSigma = 1.6;

double LayerSigma(const DaisyOptions& o, int layer) {
  return o.radius_px * (layer + 1) / (2.0 * o.rings);
}

// Gaussian blur with the reference's kernel: (int)(5 sigma) taps, made odd,
// at least 3 (the tails beyond about 2.5 sigma are cut).
void GaussianSmooth(const cv::Mat& in, double sigma, cv::Mat* out) {
  int ksize = std::max(3, static_cast<int>(5.0 * sigma));
  if (ksize % 2 == 0) ++ksize;
  cv::GaussianBlur(in, *out, cv::Size(ksize, ksize), sigma, sigma, cv::BORDER_REPLICATE);
}

// Bilinear sample of all channels of `map` at (x, y). A point whose 2x2
// neighbourhood is not at least one pixel inside the right and bottom edges,
// or that lies left of or above the image, gives a zero histogram, as in the
// reference.
void SampleHistogram(const cv::Mat& map, float x, float y, int channels, float* out) {
  if (!(x >= 0.0f && y >= 0.0f) || static_cast<int>(x) > map.cols - 3 ||
      static_cast<int>(y) > map.rows - 3) {
    std::fill(out, out + channels, 0.0f);
    return;
  }
  const int x0 = static_cast<int>(x), y0 = static_cast<int>(y);
  const int x1 = x0 + 1, y1 = y0 + 1;
  const float ax = x - x0, ay = y - y0;
  const float* p00 = map.ptr<float>(y0) + x0 * channels;
  const float* p01 = map.ptr<float>(y0) + x1 * channels;
  const float* p10 = map.ptr<float>(y1) + x0 * channels;
  const float* p11 = map.ptr<float>(y1) + x1 * channels;
  for (int c = 0; c < channels; ++c) {
    out[c] = (1 - ay) * ((1 - ax) * p00[c] + ax * p01[c]) + ay * ((1 - ax) * p10[c] + ax * p11[c]);
  }
}

void NormalizeHistogram(float* h, int n) {
  double norm = 0.0;
  for (int i = 0; i < n; ++i) norm += static_cast<double>(h[i]) * h[i];
  if (norm <= 1e-20) {  // flat region: no gradient direction at all
    std::fill(h, h + n, 0.0f);
    return;
  }
  const float inv = static_cast<float>(1.0 / std::sqrt(norm));
  for (int i = 0; i < n; ++i) h[i] *= inv;
}

}  // namespace

int DaisyDimension(const DaisyOptions& o) { return (1 + o.rings * o.ring_points) * o.orientations; }

DaisyMaps ComputeDaisyMaps(const cv::Mat& gray8, const DaisyOptions& options) {
  options.Check();
  cv::Mat unit, image, gx, gy;
  gray8.convertTo(unit, CV_32F, 1.0 / 255.0);
  cv::GaussianBlur(unit, image, cv::Size(5, 5), kImageSigma, kImageSigma, cv::BORDER_REPLICATE);
  cv::Sobel(image, gx, CV_32F, 1, 0, 1, 0.5, 0.0, cv::BORDER_REPLICATE);
  cv::Sobel(image, gy, CV_32F, 0, 1, 1, 0.5, 0.0, cv::BORDER_REPLICATE);
  const int h = options.orientations;
  std::vector<float> cosines(h), sines(h);
  for (int o = 0; o < h; ++o) {
    cosines[o] = static_cast<float>(std::cos(2.0 * kPi * o / h));
    sines[o] = static_cast<float>(std::sin(2.0 * kPi * o / h));
  }
  cv::Mat oriented(gray8.size(), CV_32FC(h));
  for (int y = 0; y < image.rows; ++y) {
    const float* dx = gx.ptr<float>(y);
    const float* dy = gy.ptr<float>(y);
    float* out = oriented.ptr<float>(y);
    for (int x = 0; x < image.cols; ++x) {
      for (int o = 0; o < h; ++o) {
        out[x * h + o] = std::max(0.0f, cosines[o] * dx[x] + sines[o] * dy[x]);
      }
    }
  }
  cv::Mat base;
  GaussianSmooth(oriented, std::sqrt(kBaseSigma * kBaseSigma - kImageSigma * kImageSigma), &base);
  DaisyMaps maps;
  maps.layers.resize(options.rings);
  GaussianSmooth(base, LayerSigma(options, 0), &maps.layers[0]);
  for (int i = 1; i < options.rings; ++i) {
    const double s0 = LayerSigma(options, i - 1), s1 = LayerSigma(options, i);
    GaussianSmooth(maps.layers[i - 1], std::sqrt(s1 * s1 - s0 * s0), &maps.layers[i]);
  }
  return maps;
}

cv::Mat DescribeDaisy(const DaisyMaps& maps, const DaisyOptions& o,
                      const std::vector<cv::KeyPoint>& keypoints) {
  const int h = o.orientations;
  const int dims = DaisyDimension(o);
  cv::Mat descriptors(static_cast<int>(keypoints.size()), dims, CV_32F);
  std::vector<float> raw(h);
  for (size_t k = 0; k < keypoints.size(); ++k) {
    const cv::KeyPoint& kp = keypoints[k];
    float* out = descriptors.ptr<float>(static_cast<int>(k));
    double angle = o.use_orientation ? kp.angle * kPi / 180.0 : 0.0;
    // Histogram bins are shifted by the (rounded) keypoint orientation.
    const int shift = o.use_orientation
                          ? static_cast<int>(std::lround(angle / (2.0 * kPi) * h)) % h
                          : 0;
    const float c = static_cast<float>(std::cos(angle)), s = static_cast<float>(std::sin(angle));
    auto write = [&](const cv::Mat& map, float x, float y, float* dst) {
      SampleHistogram(map, x, y, h, raw.data());
      for (int b = 0; b < h; ++b) dst[b] = raw[(b + shift) % h];
      if (o.normalize) NormalizeHistogram(dst, h);
    };
    write(maps.layers[0], kp.pt.x, kp.pt.y, out);
    for (int ring = 0; ring < o.rings; ++ring) {
      const double r = o.radius_px * (ring + 1) / o.rings;
      for (int j = 0; j < o.ring_points; ++j) {
        const double theta = 2.0 * kPi * j / o.ring_points;
        const float u = static_cast<float>(r * std::cos(theta)), v = static_cast<float>(r * std::sin(theta));
        float* dst = out + (1 + ring * o.ring_points + j) * h;
        write(maps.layers[ring], kp.pt.x + c * u - s * v, kp.pt.y + s * u + c * v, dst);
      }
    }
  }
  return descriptors;
}

DaisyExtractor::DaisyExtractor(const DaisyOptions& daisy, const SurfOptions& surf,
                               int max_features, double max_depth_m)
    : FeatureExtractor(max_features, max_depth_m), daisy_(daisy), surf_(surf) {
  daisy_.Check();
  surf_.Check();
}

void DaisyExtractor::DetectAndDescribe(const cv::Mat& gray, std::vector<cv::KeyPoint>* keypoints,
                                       cv::Mat* descriptors) const {
  const IntegralImage integral(gray);
  SurfOptions detector = surf_;
  detector.upright = !daisy_.use_orientation;  // orientation only when DAISY uses it
  *keypoints = DetectSurfKeypoints(integral, detector, max_features());
  if (keypoints->empty()) return;
  *descriptors = DescribeDaisy(ComputeDaisyMaps(gray, daisy_), daisy_, *keypoints);
}

}  // namespace duskmap
