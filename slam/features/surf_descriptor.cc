// SURF descriptor (Bay et al. 2008, section 4.2) and the SURF extractor.
#include <array>
#include <cmath>

#include "slam/features/surf.h"

namespace duskmap {
namespace {

constexpr float kPi = 3.14159265358979f;
constexpr int kSamples = 20;  // 20x20 samples at spacing s: 4x4 subregions of 5x5

// Gaussian (sigma 3.3 s) weights of the 20x20 sample grid, in units of s.
const std::array<float, kSamples * kSamples>& GridWeights() {
  static const auto kWeights = [] {
    std::array<float, kSamples * kSamples> w{};
    const float sigma = 3.3f;
    for (int b = 0; b < kSamples; ++b) {
      for (int a = 0; a < kSamples; ++a) {
        const float u = a - 9.5f, v = b - 9.5f;
        w[b * kSamples + a] = std::exp(-(u * u + v * v) / (2.0f * sigma * sigma));
      }
    }
    return w;
  }();
  return kWeights;
}

void DescribeOne(const IntegralImage& integral, const cv::KeyPoint& kp, bool extended,
                 float* out) {
  const int dims = extended ? 128 : 64;
  std::fill(out, out + dims, 0.0f);
  const float s = 1.2f * kp.size / 9.0f;
  const float angle = kp.angle * kPi / 180.0f;
  const float c = std::cos(angle), sn = std::sin(angle);
  const int half = std::max(1, static_cast<int>(std::lround(s)));  // Haar side 2s
  const auto& weights = GridWeights();
  for (int b = 0; b < kSamples; ++b) {
    for (int a = 0; a < kSamples; ++a) {
      const float u = (a - 9.5f) * s, v = (b - 9.5f) * s;
      const int x = static_cast<int>(std::lround(kp.pt.x + c * u - sn * v));
      const int y = static_cast<int>(std::lround(kp.pt.y + sn * u + c * v));
      float dx, dy;
      integral.Haar(x, y, half, &dx, &dy);
      const float w = weights[b * kSamples + a];
      // Responses in the keypoint frame.
      const float rx = w * (c * dx + sn * dy);
      const float ry = w * (-sn * dx + c * dy);
      float* sub = out + ((b / 5) * 4 + (a / 5)) * (extended ? 8 : 4);
      if (!extended) {
        sub[0] += rx;
        sub[1] += std::abs(rx);
        sub[2] += ry;
        sub[3] += std::abs(ry);
      } else {
        float* x_part = sub + (ry < 0.0f ? 0 : 2);
        x_part[0] += rx;
        x_part[1] += std::abs(rx);
        float* y_part = sub + (rx < 0.0f ? 4 : 6);
        y_part[0] += ry;
        y_part[1] += std::abs(ry);
      }
    }
  }
  double norm = 0.0;
  for (int k = 0; k < dims; ++k) norm += static_cast<double>(out[k]) * out[k];
  if (norm <= 0.0) return;
  const float inv = static_cast<float>(1.0 / std::sqrt(norm));
  for (int k = 0; k < dims; ++k) out[k] *= inv;
}

}  // namespace

cv::Mat DescribeSurf(const IntegralImage& integral, const std::vector<cv::KeyPoint>& keypoints,
                     bool extended) {
  cv::Mat descriptors(static_cast<int>(keypoints.size()), extended ? 128 : 64, CV_32F);
  for (size_t i = 0; i < keypoints.size(); ++i) {
    DescribeOne(integral, keypoints[i], extended, descriptors.ptr<float>(static_cast<int>(i)));
  }
  return descriptors;
}

SurfExtractor::SurfExtractor(const SurfOptions& options, int max_features, double max_depth_m)
    : FeatureExtractor(max_features, max_depth_m), options_(options) {
  options_.Check();
}

void SurfExtractor::DetectAndDescribe(const cv::Mat& gray, std::vector<cv::KeyPoint>* keypoints,
                                      cv::Mat* descriptors) const {
  const IntegralImage integral(gray);
  *keypoints = DetectSurfKeypoints(integral, options_, max_features());
  *descriptors = DescribeSurf(integral, *keypoints, options_.extended);
}

}  // namespace duskmap
