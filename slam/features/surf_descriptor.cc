// SURF descriptor (Bay et al. 2008, section 4.2, as OpenCV's SURF computes it)
// and the SURF extractor.
#include <algorithm>
#include <array>
#include <cmath>

#include <opencv2/imgproc.hpp>

#include "slam/core/check.h"
#include "slam/features/surf.h"

namespace duskmap {
namespace {

constexpr float kPi = 3.14159265358979f;
constexpr int kPatch = 20;  // 20x20 gradients at spacing s: 4x4 subregions of 5x5

// Gaussian (sigma 3.3 s) weights of the 20x20 gradient grid.
const std::array<float, kPatch * kPatch>& GridWeights() {
  static const auto kWeights = [] {
    std::array<float, kPatch * kPatch> w{};
    const float sigma = 3.3f;
    for (int b = 0; b < kPatch; ++b) {
      for (int a = 0; a < kPatch; ++a) {
        const float u = a - 9.5f, v = b - 9.5f;
        w[b * kPatch + a] = std::exp(-(u * u + v * v) / (2.0f * sigma * sigma));
      }
    }
    return w;
  }();
  return kWeights;
}

// The (kPatch + 1)^2 patch the gradients are taken on, as OpenCV's SURF
// builds it: a window of (int)(21 s) pixels around the keypoint, its columns
// along the orientation, sampled bilinearly (OpenCV's fixed-point warp, to
// 1/32 pixel; the nearest edge pixel beyond the image; whole pixels without
// orientation) in 8 bits, then area-averaged down to 21x21 so that one patch
// pixel covers s x s image pixels.
void SamplePatch(const cv::Mat& gray, const cv::KeyPoint& kp, bool upright, float s,
                 cv::Mat* window, cv::Mat* patch) {
  const int side = std::max(1, static_cast<int>((kPatch + 1) * s));
  window->create(side, side, CV_8UC1);
  const float offset = -0.5f * (side - 1);
  const int max_x = gray.cols - 1, max_y = gray.rows - 1;
  if (upright) {
    const int x0 = static_cast<int>(std::lround(kp.pt.x + offset));
    const int y0 = static_cast<int>(std::lround(kp.pt.y + offset));
    for (int r = 0; r < side; ++r) {
      uint8_t* out = window->ptr<uint8_t>(r);
      const int y = std::clamp(y0 + r, 0, max_y);
      for (int c = 0; c < side; ++c) out[c] = gray.at<uint8_t>(y, std::clamp(x0 + c, 0, max_x));
    }
  } else {
    // Column step (cos, sin) along the orientation, row step (-sin, cos);
    // bilinear samples, the nearest edge pixel beyond the image.
    const double angle = kp.angle * kPi / 180.0;
    const double cs = std::cos(angle), sn = std::sin(angle);
    const cv::Matx23d window_to_image(cs, -sn, kp.pt.x + offset * (cs - sn),  //
                                      sn, cs, kp.pt.y + offset * (sn + cs));
    cv::warpAffine(gray, *window, window_to_image, window->size(),
                   cv::INTER_LINEAR | cv::WARP_INVERSE_MAP, cv::BORDER_REPLICATE);
  }
  cv::resize(*window, *patch, cv::Size(kPatch + 1, kPatch + 1), 0, 0, cv::INTER_AREA);
}

void DescribeOne(const cv::Mat& gray, const cv::KeyPoint& kp, bool extended, bool upright,
                 cv::Mat* window, cv::Mat* patch, float* out) {
  const int dims = extended ? 128 : 64;
  std::fill(out, out + dims, 0.0f);
  const float s = 1.2f * kp.size / 9.0f;
  SamplePatch(gray, kp, upright, s, window, patch);
  const auto& weights = GridWeights();
  for (int b = 0; b < kPatch; ++b) {
    const uint8_t* p0 = patch->ptr<uint8_t>(b);
    const uint8_t* p1 = patch->ptr<uint8_t>(b + 1);
    for (int a = 0; a < kPatch; ++a) {
      // Haar wavelets of side 2s in the keypoint frame: 2x2 patch differences.
      const float w = weights[b * kPatch + a];
      const float rx = w * static_cast<float>(p0[a + 1] - p0[a] + p1[a + 1] - p1[a]);
      const float ry = w * static_cast<float>(p1[a] - p0[a] + p1[a + 1] - p0[a + 1]);
      float* sub = out + ((b / 5) * 4 + (a / 5)) * (extended ? 8 : 4);
      if (!extended) {
        sub[0] += rx;
        sub[1] += std::abs(rx);
        sub[2] += ry;
        sub[3] += std::abs(ry);
      } else {
        float* x_part = sub + (ry >= 0.0f ? 0 : 2);
        x_part[0] += rx;
        x_part[1] += std::abs(rx);
        float* y_part = sub + (rx >= 0.0f ? 4 : 6);
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

cv::Mat DescribeSurf(const cv::Mat& gray, const std::vector<cv::KeyPoint>& keypoints,
                     bool extended, bool upright) {
  SLAM_CHECK(gray.type() == CV_8UC1);
  cv::Mat descriptors(static_cast<int>(keypoints.size()), extended ? 128 : 64, CV_32F);
  cv::Mat window, patch;
  for (size_t i = 0; i < keypoints.size(); ++i) {
    DescribeOne(gray, keypoints[i], extended, upright, &window, &patch,
                descriptors.ptr<float>(static_cast<int>(i)));
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
  *descriptors = DescribeSurf(gray, *keypoints, options_.extended, options_.upright);
}

}  // namespace duskmap
