#include "slam/features/eval/homography_metrics.h"

#include <algorithm>
#include <cmath>

#include <opencv2/calib3d.hpp>
#include <opencv2/features2d.hpp>

#include "slam/core/check.h"

namespace duskmap {
namespace {

bool Inside(const cv::Point2d& p, const cv::Size& size) {
  return p.x >= 0.0 && p.y >= 0.0 && p.x <= size.width - 1.0 && p.y <= size.height - 1.0;
}

// Counts keypoints of `from` that project inside `to_size` (*visible) and of
// those, the ones with a keypoint of `to` within tolerance.
int CountRepeated(const std::vector<cv::KeyPoint>& from, const std::vector<cv::KeyPoint>& to,
                  const cv::Size& to_size, const cv::Matx33d& to_from, double tolerance_px,
                  int* visible) {
  *visible = 0;
  int repeated = 0;
  const double tol2 = tolerance_px * tolerance_px;
  for (const cv::KeyPoint& kp : from) {
    const cv::Point2d p = ApplyHomography(to_from, kp.pt);
    if (!Inside(p, to_size)) continue;
    ++*visible;
    for (const cv::KeyPoint& other : to) {
      const double dx = other.pt.x - p.x, dy = other.pt.y - p.y;
      if (dx * dx + dy * dy <= tol2) {
        ++repeated;
        break;
      }
    }
  }
  return repeated;
}

int CountVisible(const std::vector<cv::KeyPoint>& from, const cv::Size& to_size,
                 const cv::Matx33d& to_from) {
  int visible = 0;
  for (const cv::KeyPoint& kp : from) visible += Inside(ApplyHomography(to_from, kp.pt), to_size);
  return visible;
}

void EstimateHomography(const FrameFeatures& reference, const cv::Size& reference_size,
                        const FrameFeatures& target, const std::vector<cv::DMatch>& matches,
                        const cv::Matx33d& truth, const HomographyMetricsOptions& options,
                        PairMetrics* m) {
  if (matches.size() < 4) return;
  std::vector<cv::Point2f> src, dst;
  for (const cv::DMatch& match : matches) {
    src.push_back(reference.keypoints[match.queryIdx].pt);
    dst.push_back(target.keypoints[match.trainIdx].pt);
  }
  cv::setRNGSeed(7);  // findHomography's RANSAC draws from OpenCV's global RNG
  const cv::Mat estimate = cv::findHomography(src, dst, cv::RANSAC, options.ransac_px);
  if (estimate.empty()) return;
  const cv::Matx33d h(estimate);
  const double w = reference_size.width - 1.0, ht = reference_size.height - 1.0;
  const cv::Point2d corners[4] = {{0, 0}, {w, 0}, {0, ht}, {w, ht}};
  double error = 0.0;
  for (const cv::Point2d& c : corners) {
    const cv::Point2d d = ApplyHomography(h, c) - ApplyHomography(truth, c);
    error += std::hypot(d.x, d.y) / 4.0;
  }
  m->homography_estimated = std::isfinite(error);
  m->corner_error_px = error;
  m->homography_correct = m->homography_estimated && error < options.corner_error_px;
}

}  // namespace

void HomographyMetricsOptions::Check() const {
  SLAM_THROW_IF_NOT(ConfigError, repeatability_px > 0) << "metrics.repeatability_px: must be > 0";
  SLAM_THROW_IF_NOT(ConfigError, correct_match_px > 0) << "metrics.correct_match_px: must be > 0";
  SLAM_THROW_IF_NOT(ConfigError, ransac_px > 0) << "metrics.ransac_px: must be > 0";
  SLAM_THROW_IF_NOT(ConfigError, corner_error_px > 0) << "metrics.corner_error_px: must be > 0";
  for (double t : mma_px) SLAM_THROW_IF_NOT(ConfigError, t > 0) << "metrics.mma_px: must be > 0";
}

cv::Point2d ApplyHomography(const cv::Matx33d& h, const cv::Point2d& p) {
  const cv::Vec3d q = h * cv::Vec3d(p.x, p.y, 1.0);
  return cv::Point2d(q[0] / q[2], q[1] / q[2]);
}

std::vector<cv::DMatch> MutualNearestMatches(const FrameFeatures& a, const FrameFeatures& b) {
  std::vector<cv::DMatch> matches;
  if (a.empty() || b.empty()) return matches;
  SLAM_THROW_IF_NOT(InputError, a.descriptors.type() == b.descriptors.type() &&
                                    a.descriptors.cols == b.descriptors.cols)
      << "matching: descriptors of different types or sizes";
  const int norm = a.kind == DescriptorKind::kBinary ? cv::NORM_HAMMING : cv::NORM_L2;
  cv::BFMatcher matcher(norm, /*crossCheck=*/true);
  matcher.match(a.descriptors, b.descriptors, matches);
  return matches;
}

double Repeatability(const std::vector<cv::KeyPoint>& reference, const cv::Size& reference_size,
                     const std::vector<cv::KeyPoint>& target, const cv::Size& target_size,
                     const cv::Matx33d& target_from_reference, double tolerance_px) {
  int visible_ref = 0, visible_tgt = 0;
  const int rep_ref = CountRepeated(reference, target, target_size, target_from_reference,
                                    tolerance_px, &visible_ref);
  const int rep_tgt = CountRepeated(target, reference, reference_size,
                                    target_from_reference.inv(), tolerance_px, &visible_tgt);
  const int visible = visible_ref + visible_tgt;
  return visible == 0 ? 0.0 : static_cast<double>(rep_ref + rep_tgt) / visible;
}

PairMetrics EvaluatePair(const FrameFeatures& reference, const cv::Size& reference_size,
                         const FrameFeatures& target, const cv::Size& target_size,
                         const cv::Matx33d& truth, const HomographyMetricsOptions& options) {
  options.Check();
  PairMetrics m;
  m.reference_keypoints = static_cast<int>(reference.size());
  m.target_keypoints = static_cast<int>(target.size());
  m.repeatability = Repeatability(reference.keypoints, reference_size, target.keypoints,
                                  target_size, truth, options.repeatability_px);
  const std::vector<cv::DMatch> matches = MutualNearestMatches(reference, target);
  m.matches = static_cast<int>(matches.size());
  std::array<int, 3> within = {0, 0, 0};
  for (const cv::DMatch& match : matches) {
    const cv::Point2d d = ApplyHomography(truth, reference.keypoints[match.queryIdx].pt) -
                          cv::Point2d(target.keypoints[match.trainIdx].pt);
    const double error = std::hypot(d.x, d.y);
    m.correct_matches += error < options.correct_match_px;
    for (size_t t = 0; t < within.size(); ++t) within[t] += error < options.mma_px[t];
  }
  for (size_t t = 0; t < within.size(); ++t) {
    m.mma[t] = m.matches == 0 ? 0.0 : static_cast<double>(within[t]) / m.matches;
  }
  const int visible = std::min(CountVisible(reference.keypoints, target_size, truth),
                               CountVisible(target.keypoints, reference_size, truth.inv()));
  m.matching_score = visible == 0 ? 0.0 : static_cast<double>(m.correct_matches) / visible;
  EstimateHomography(reference, reference_size, target, matches, truth, options, &m);
  return m;
}

}  // namespace duskmap
