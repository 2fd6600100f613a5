#include "slam/eval/realism.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>

#include "slam/core/check.h"
#include "slam/core/timer.h"

namespace duskmap {
namespace {

struct FrameFeatureSet {
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
  std::vector<Eigen::Vector3d> points;  // camera frame; NaN without depth
};

struct AnchorFrame {
  bool present = false;
  int frame_index = 0;
  Rigid3d world_from_camera;
  PinholeCamera camera;
  FrameFeatureSet sift, orb;
};

double PoseGap(const Rigid3d& a, const Rigid3d& b) {
  const Eigen::Vector3d za = a.rotation * Eigen::Vector3d::UnitZ(), zb = b.rotation * Eigen::Vector3d::UnitZ();
  const double angle = std::acos(std::clamp(za.dot(zb), -1.0, 1.0));
  return (a.translation - b.translation).norm() + 0.5 * angle;
}

bool WithinGaps(const RealismOptions& o, const Rigid3d& a, const Rigid3d& b) {
  const Eigen::Vector3d za = a.rotation * Eigen::Vector3d::UnitZ(), zb = b.rotation * Eigen::Vector3d::UnitZ();
  const double angle_deg = std::acos(std::clamp(za.dot(zb), -1.0, 1.0)) * 180.0 / M_PI;
  return (a.translation - b.translation).norm() <= o.max_position_gap_m && angle_deg <= o.max_angle_gap_deg;
}

FrameFeatureSet Extract(cv::Feature2D& detector, const cv::Mat& gray, const cv::Mat& depth_m,
                        const PinholeCamera& camera) {
  FrameFeatureSet f;
  detector.detectAndCompute(gray, cv::noArray(), f.keypoints, f.descriptors);
  for (const cv::KeyPoint& k : f.keypoints) {
    const int u = std::clamp(static_cast<int>(std::lround(k.pt.x)), 0, depth_m.cols - 1);
    const int v = std::clamp(static_cast<int>(std::lround(k.pt.y)), 0, depth_m.rows - 1);
    const float d = depth_m.at<float>(v, u);
    f.points.push_back(d > 0.0f ? camera.Unproject(k.pt.x, k.pt.y, d)
                                : Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN()));
  }
  return f;
}

struct PairResult {
  int inliers = 0;
  int matches_with_depth = 0;
};

PairResult MatchPair(const RealismOptions& o, const FrameFeatureSet& a, const FrameFeatureSet& b,
                     const AnchorFrame& fa, const AnchorFrame& fb, int norm) {
  PairResult result;
  if (a.descriptors.empty() || b.descriptors.rows < 2) return result;
  cv::BFMatcher matcher(norm);
  std::vector<std::vector<cv::DMatch>> knn;
  matcher.knnMatch(a.descriptors, b.descriptors, knn, 2);
  const Rigid3d b_from_a = fb.world_from_camera.Inverse() * fa.world_from_camera;
  for (const auto& m : knn) {
    if (m.size() < 2 || m[0].distance >= o.ratio_test * m[1].distance) continue;
    const Eigen::Vector3d& p = a.points[m[0].queryIdx];
    if (!p.allFinite()) continue;
    ++result.matches_with_depth;
    Eigen::Vector2d pixel;
    if (!fb.camera.Project(b_from_a * p, &pixel)) continue;
    const cv::Point2f& q = b.keypoints[m[0].trainIdx].pt;
    if ((pixel - Eigen::Vector2d(q.x, q.y)).norm() <= o.max_reprojection_px) ++result.inliers;
  }
  return result;
}

double Median(std::vector<double> values) {
  if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(values.begin(), values.end());
  const size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

// One pass over a session: for each anchor keeps the nearest frame.
std::vector<AnchorFrame> CollectAnchorFrames(const RealismOptions& o, SessionReader& reader,
                                             const std::vector<Rigid3d>& anchors,
                                             std::vector<Rigid3d>* all_poses) {
  std::vector<std::optional<RgbdFrame>> best(anchors.size());
  std::vector<double> best_gap(anchors.size(), std::numeric_limits<double>::infinity());
  while (std::optional<RgbdFrame> frame = reader.Next()) {
    SLAM_THROW_IF_NOT(InputError, frame->world_from_camera.has_value())
        << "session " << reader.info().name << ": frame " << frame->frame_index << " has no ground truth";
    const Rigid3d pose = *frame->world_from_camera;
    if (all_poses != nullptr) all_poses->push_back(pose);
    for (size_t i = 0; i < anchors.size(); ++i) {
      const double gap = PoseGap(anchors[i], pose);
      if (gap < best_gap[i] && WithinGaps(o, anchors[i], pose)) {
        best_gap[i] = gap;
        best[i] = *frame;
      }
    }
  }
  cv::Ptr<cv::SIFT> sift = cv::SIFT::create(o.max_features, 3, o.sift_contrast_threshold);
  cv::Ptr<cv::ORB> orb = cv::ORB::create(o.max_features);
  std::vector<AnchorFrame> out(anchors.size());
  for (size_t i = 0; i < anchors.size(); ++i) {
    if (!best[i]) continue;
    cv::Mat gray;
    cv::cvtColor(best[i]->bgr, gray, cv::COLOR_BGR2GRAY);
    out[i].present = true;
    out[i].frame_index = static_cast<int>(best[i]->frame_index);
    out[i].world_from_camera = *best[i]->world_from_camera;
    out[i].camera = best[i]->camera;
    out[i].sift = Extract(*sift, gray, best[i]->depth_m, best[i]->camera);
    out[i].orb = Extract(*orb, gray, best[i]->depth_m, best[i]->camera);
  }
  return out;
}

}  // namespace

void RealismOptions::Check() const {
  // Upper bounds too: `--max-features 1e9` reached the detectors as a
  // billion-keypoint request (bad_alloc); a threshold of 1e308 px accepts
  // every match. Each message names the field and the flag that sets it.
  SLAM_THROW_IF_NOT(ConfigError, frame_step >= 1 && frame_step <= 100000)
      << "frame_step (--frame-step) must be in [1, 100000], got " << frame_step;
  SLAM_THROW_IF_NOT(ConfigError, max_features >= 10 && max_features <= kMaxRealismFeatures)
      << "max_features (--max-features) must be in [10, " << kMaxRealismFeatures << "], got " << max_features;
  SLAM_THROW_IF_NOT(ConfigError, sift_contrast_threshold > 0.0 && sift_contrast_threshold < 1.0)
      << "sift_contrast_threshold (--sift-contrast) must be in (0, 1), got " << sift_contrast_threshold;
  SLAM_THROW_IF_NOT(ConfigError, ratio_test > 0 && ratio_test <= 1) << "ratio_test must be in (0, 1], got " << ratio_test;
  SLAM_THROW_IF_NOT(ConfigError, max_reprojection_px > 0 && max_reprojection_px <= kMaxRealismReprojectionPx)
      << "max_reprojection_px (--max-error-px) must be in (0, " << kMaxRealismReprojectionPx << "], got "
      << max_reprojection_px;
  SLAM_THROW_IF_NOT(ConfigError, max_position_gap_m > 0 && max_angle_gap_deg > 0) << "correspondence gaps must be > 0";
  SLAM_THROW_IF_NOT(ConfigError, min_correct_matches >= 1 && min_correct_matches <= max_features)
      << "min_correct_matches (--min-correct) must be in [1, max_features = " << max_features << "], got "
      << min_correct_matches;
}

RealismReport ComputeRealism(const DatasetReader& dataset, const RealismOptions& options) {
  options.Check();
  Stopwatch watch;
  RealismReport report;
  const std::vector<SessionInfo> sessions = dataset.Sessions();
  SLAM_THROW_IF_NOT(InputError, sessions.size() >= 2) << "dataset-stats needs at least 2 sessions";
  for (const SessionInfo& s : sessions) {
    SLAM_THROW_IF_NOT(InputError, s.has_ground_truth) << "session " << s.name << ": no ground truth";
    report.sessions.push_back(s.name);
    report.clock_times.push_back(s.clock_time.value_or(""));
  }
  // Anchors: every frame_step-th ground-truth pose of the first session.
  std::vector<Rigid3d> first_poses;
  {
    std::unique_ptr<SessionReader> reader = dataset.OpenSession(sessions[0].name);
    while (std::optional<RgbdFrame> f = reader->Next()) {
      SLAM_THROW_IF_NOT(InputError, f->world_from_camera.has_value())
          << "session " << sessions[0].name << ": frame " << f->frame_index << " has no ground truth";
      first_poses.push_back(*f->world_from_camera);
    }
  }
  std::vector<Rigid3d> anchors;
  for (size_t k = 0; k < first_poses.size(); k += options.frame_step) anchors.push_back(first_poses[k]);
  report.anchors = static_cast<int>(anchors.size());
  std::vector<std::vector<AnchorFrame>> frames;
  for (const SessionInfo& s : sessions) {
    std::unique_ptr<SessionReader> reader = dataset.OpenSession(s.name);
    frames.push_back(CollectAnchorFrames(options, *reader, anchors, nullptr));
  }
  const int n = static_cast<int>(sessions.size());
  const double nan = std::numeric_limits<double>::quiet_NaN();
  report.sift_inlier_ratio = Eigen::MatrixXd::Constant(n, n, nan);
  report.orb_inlier_ratio = Eigen::MatrixXd::Constant(n, n, nan);
  report.sift_found_fraction = Eigen::MatrixXd::Constant(n, n, nan);
  report.sift_median_inliers = Eigen::MatrixXd::Constant(n, n, nan);
  for (int a = 0; a < n; ++a) {
    for (int b = a + 1; b < n; ++b) {
      std::vector<double> sift_ratios, orb_ratios, sift_inliers;
      int found = 0;
      for (size_t k = 0; k < anchors.size(); ++k) {
        const AnchorFrame& fa = frames[a][k];
        const AnchorFrame& fb = frames[b][k];
        if (!fa.present || !fb.present) continue;
        const PairResult s = MatchPair(options, fa.sift, fb.sift, fa, fb, cv::NORM_L2);
        const PairResult o = MatchPair(options, fa.orb, fb.orb, fa, fb, cv::NORM_HAMMING);
        sift_ratios.push_back(s.matches_with_depth > 0 ? static_cast<double>(s.inliers) / s.matches_with_depth : 0.0);
        orb_ratios.push_back(o.matches_with_depth > 0 ? static_cast<double>(o.inliers) / o.matches_with_depth : 0.0);
        sift_inliers.push_back(s.inliers);
        if (s.inliers >= options.min_correct_matches) ++found;
        RealismPair pair;
        pair.session_a = a;
        pair.session_b = b;
        pair.anchor = static_cast<int>(k);
        pair.frame_a = fa.frame_index;
        pair.frame_b = fb.frame_index;
        pair.sift_keypoints_a = static_cast<int>(fa.sift.keypoints.size());
        pair.sift_keypoints_b = static_cast<int>(fb.sift.keypoints.size());
        pair.sift_matches = s.matches_with_depth;
        pair.sift_correct = s.inliers;
        pair.orb_matches = o.matches_with_depth;
        pair.orb_correct = o.inliers;
        report.pairs.push_back(pair);
      }
      if (sift_ratios.empty()) continue;
      report.sift_inlier_ratio(a, b) = report.sift_inlier_ratio(b, a) = Median(sift_ratios);
      report.orb_inlier_ratio(a, b) = report.orb_inlier_ratio(b, a) = Median(orb_ratios);
      report.sift_median_inliers(a, b) = report.sift_median_inliers(b, a) = Median(sift_inliers);
      report.sift_found_fraction(a, b) = report.sift_found_fraction(b, a) =
          static_cast<double>(found) / sift_ratios.size();
    }
  }
  report.wall_s = watch.ElapsedMs() / 1000.0;
  return report;
}

}  // namespace duskmap
