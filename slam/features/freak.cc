#include "slam/features/freak.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <tuple>

#include "slam/core/check.h"
#include "slam/features/corner_detectors.h"

namespace duskmap {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr float kSmallestKeypointSize = 7.0f;  // FAST's keypoint size: scale 1

FreakPattern BuildPattern() {
  FreakPattern p;
  // Ring radii shrink towards the centre with overlapping fields (the
  // retina-like layout of the paper's figure 4), sigma = radius / 2.
  const double big_r = 2.0 / 3.0, small_r = 2.0 / 24.0, unit = (big_r - small_r) / 21.0;
  const double radius[7] = {big_r,           big_r - 6 * unit,  big_r - 11 * unit, big_r - 15 * unit,
                            big_r - 18 * unit, big_r - 20 * unit, small_r};
  for (int ring = 0; ring < 7; ++ring) {
    for (int k = 0; k < 6; ++k) {
      const double theta = 2.0 * kPi * k / 6.0 + ring * kPi / 6.0;  // alternate rings rotated
      p.centers[ring * 6 + k] = cv::Point2f(static_cast<float>(radius[ring] * std::cos(theta)),
                                            static_cast<float>(radius[ring] * std::sin(theta)));
      p.sigmas[ring * 6 + k] = static_cast<float>(radius[ring] / 2.0);
    }
  }
  p.centers[42] = cv::Point2f(0.0f, 0.0f);
  p.sigmas[42] = static_cast<float>(small_r / 2.0);

  struct Candidate {
    uint8_t a, b;
    float coarseness, distance;
  };
  std::vector<Candidate> all;
  for (int a = 0; a < FreakPattern::kFields; ++a) {
    for (int b = a + 1; b < FreakPattern::kFields; ++b) {
      const cv::Point2f d = p.centers[a] - p.centers[b];
      all.push_back({static_cast<uint8_t>(a), static_cast<uint8_t>(b),
                     std::min(p.sigmas[a], p.sigmas[b]), std::hypot(d.x, d.y)});
    }
  }
  auto key = [](const Candidate& c) { return std::make_tuple(c.a, c.b); };
  std::vector<Candidate> by_coarseness = all;
  std::stable_sort(by_coarseness.begin(), by_coarseness.end(),
                   [&](const Candidate& x, const Candidate& y) {
                     // Rounded so that equal ring sizes compare equal despite float noise.
                     const long cx = std::lround(x.coarseness * 1e5), cy = std::lround(y.coarseness * 1e5);
                     if (cx != cy) return cx > cy;
                     const long dx = std::lround(x.distance * 1e5), dy = std::lround(y.distance * 1e5);
                     if (dx != dy) return dx > dy;
                     return key(x) < key(y);
                   });
  for (int i = 0; i < FreakPattern::kPairs; ++i) {
    p.pairs.push_back({by_coarseness[i].a, by_coarseness[i].b});
  }
  std::vector<Candidate> by_distance = all;
  std::stable_sort(by_distance.begin(), by_distance.end(),
                   [&](const Candidate& x, const Candidate& y) {
                     const long dx = std::lround(x.distance * 1e5), dy = std::lround(y.distance * 1e5);
                     if (dx != dy) return dx > dy;
                     return key(x) < key(y);
                   });
  for (int i = 0; i < FreakPattern::kOrientationPairs; ++i) {
    p.orientation_pairs.push_back({by_distance[i].a, by_distance[i].b});
  }
  return p;
}

// Mean intensities of the 43 fields around kp, pattern rotated by (c, s).
void SampleFields(const IntegralImage& integral, const FreakPattern& p, const cv::Point2f& center,
                  float scale_px, float c, float s, std::array<float, FreakPattern::kFields>* out) {
  for (int f = 0; f < FreakPattern::kFields; ++f) {
    const float px = p.centers[f].x * scale_px, py = p.centers[f].y * scale_px;
    const int x = static_cast<int>(std::lround(center.x + c * px - s * py));
    const int y = static_cast<int>(std::lround(center.y + s * px + c * py));
    const int h = std::max(1, static_cast<int>(std::lround(p.sigmas[f] * scale_px)));
    const int sum = integral.BoxSumClipped(x - h, y - h, x + h + 1, y + h + 1);
    (*out)[f] = static_cast<float>(sum) / static_cast<float>((2 * h + 1) * (2 * h + 1));
  }
}

}  // namespace

const FreakPattern& GetFreakPattern() {
  static const FreakPattern kPattern = BuildPattern();
  return kPattern;
}

cv::Mat DescribeFreak(const IntegralImage& integral, const FreakOptions& options,
                      std::vector<cv::KeyPoint>* keypoints) {
  const FreakPattern& p = GetFreakPattern();
  // Remove keypoints whose outermost field (radius + sigma = 1 pattern unit) leaves the image.
  std::vector<cv::KeyPoint> kept;
  std::vector<float> scales;
  for (const cv::KeyPoint& kp : *keypoints) {
    const float scale = options.scale_normalized
                            ? std::max(1.0f, kp.size / kSmallestKeypointSize)
                            : 1.0f;
    const float scale_px = static_cast<float>(options.pattern_scale) * scale;
    if (kp.pt.x - scale_px < 0 || kp.pt.y - scale_px < 0 ||
        kp.pt.x + scale_px > integral.width() - 1 || kp.pt.y + scale_px > integral.height() - 1) {
      continue;
    }
    kept.push_back(kp);
    scales.push_back(scale_px);
  }
  *keypoints = std::move(kept);
  cv::Mat descriptors(static_cast<int>(keypoints->size()), FreakPattern::kPairs / 8, CV_8U,
                      cv::Scalar(0));
  std::array<float, FreakPattern::kFields> fields;
  for (size_t k = 0; k < keypoints->size(); ++k) {
    cv::KeyPoint& kp = (*keypoints)[k];
    float c = 1.0f, s = 0.0f;
    if (options.orientation_normalized) {
      SampleFields(integral, p, kp.pt, scales[k], 1.0f, 0.0f, &fields);
      double ox = 0.0, oy = 0.0;
      for (const auto& pair : p.orientation_pairs) {
        const cv::Point2f d = p.centers[pair[0]] - p.centers[pair[1]];
        const double w = (fields[pair[0]] - fields[pair[1]]) / std::hypot(d.x, d.y);
        ox += w * d.x;
        oy += w * d.y;
      }
      const double angle = std::atan2(oy, ox);
      c = static_cast<float>(std::cos(angle));
      s = static_cast<float>(std::sin(angle));
      double degrees = angle * 180.0 / kPi;
      if (degrees < 0.0) degrees += 360.0;
      kp.angle = static_cast<float>(degrees >= 360.0 ? degrees - 360.0 : degrees);
    }
    SampleFields(integral, p, kp.pt, scales[k], c, s, &fields);
    uint8_t* out = descriptors.ptr<uint8_t>(static_cast<int>(k));
    for (int i = 0; i < FreakPattern::kPairs; ++i) {
      if (fields[p.pairs[i][0]] > fields[p.pairs[i][1]]) out[i / 8] |= uint8_t(1u << (i % 8));
    }
  }
  return descriptors;
}

FreakExtractor::FreakExtractor(const FreakOptions& freak, const GfttOptions& gftt,
                               const FastOptions& fast, int max_features, double max_depth_m)
    : FeatureExtractor(max_features, max_depth_m), freak_(freak), gftt_(gftt), fast_(fast) {
  freak_.Check();
  gftt_.Check();
  fast_.Check();
}

void FreakExtractor::DetectAndDescribe(const cv::Mat& gray, std::vector<cv::KeyPoint>* keypoints,
                                       cv::Mat* descriptors) const {
  if (freak_.detector == "fast") {
    *keypoints = DetectFast(gray, fast_);
    cv::Mat none;
    KeepStrongest(2 * max_features(), keypoints, &none);
  } else {
    *keypoints = DetectGftt(gray, gftt_, 2 * max_features());
  }
  const IntegralImage integral(gray);
  *descriptors = DescribeFreak(integral, freak_, keypoints);
  if (keypoints->size() > static_cast<size_t>(max_features())) {
    keypoints->resize(max_features());
    *descriptors = descriptors->rowRange(0, max_features()).clone();
  }
}

}  // namespace duskmap
