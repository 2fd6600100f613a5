#include "slam/training/correspondence.h"

#include <algorithm>
#include <cmath>
#include <tuple>

#include "slam/core/check.h"

namespace duskmap {
namespace {

constexpr double kPi = 3.14159265358979323846;

// The depth at the pixel holding (x, y), or 0 outside the image.
double DepthAt(const cv::Mat& depth_m, double x, double y) {
  const int u = static_cast<int>(std::lround(x));
  const int v = static_cast<int>(std::lround(y));
  if (u < 0 || v < 0 || u >= depth_m.cols || v >= depth_m.rows) return 0.0;
  const float z = depth_m.at<float>(v, u);
  return std::isfinite(z) && z > 0.0f ? z : 0.0;
}

double WrapDeg(double angle_deg) {
  double wrapped = std::fmod(angle_deg, 360.0);
  if (wrapped < 0.0) wrapped += 360.0;
  return wrapped >= 360.0 ? 0.0 : wrapped;
}

}  // namespace

void CorrespondenceOptions::Check() const {
  SLAM_THROW_IF_NOT(ConfigError, max_offset_px > 0.0) << "max_offset_px: must be > 0, got " << max_offset_px;
  SLAM_THROW_IF_NOT(ConfigError, max_scale_ratio >= 1.0)
      << "max_scale_ratio: must be >= 1, got " << max_scale_ratio;
  SLAM_THROW_IF_NOT(ConfigError, max_angle_deg > 0.0 && max_angle_deg <= 180.0)
      << "max_angle_deg: must be in (0, 180], got " << max_angle_deg;
  SLAM_THROW_IF_NOT(ConfigError, occlusion_tolerance > 0.0 && occlusion_tolerance < 1.0)
      << "occlusion_tolerance: must be in (0, 1), got " << occlusion_tolerance;
}

double AngleDifferenceDeg(double a_deg, double b_deg) {
  const double d = WrapDeg(a_deg - b_deg);
  return d > 180.0 ? 360.0 - d : d;
}

PredictedKeypoint PredictKeypoint(const cv::KeyPoint& keypoint, const ViewGeometry& a, const ViewGeometry& b,
                                  double occlusion_tolerance) {
  PredictedKeypoint out;
  const double z_a = DepthAt(a.depth_m, keypoint.pt.x, keypoint.pt.y);
  if (z_a <= 0.0) return out;  // kNoDepth
  out.point_in_world = a.world_from_camera * a.camera.Unproject(keypoint.pt.x, keypoint.pt.y, z_a);
  const Rigid3d b_from_world = b.world_from_camera.Inverse();
  const Eigen::Vector3d in_b = b_from_world * out.point_in_world;
  Eigen::Vector2d pixel;
  if (!b.camera.Project(in_b, &pixel)) {
    out.status = PredictionStatus::kBehindCamera;
    return out;
  }
  out.pt_in_b = cv::Point2f(static_cast<float>(pixel.x()), static_cast<float>(pixel.y()));
  if (!b.camera.InImage(pixel.x(), pixel.y())) {
    out.status = PredictionStatus::kOutsideImage;
    return out;
  }
  const double z_seen = DepthAt(b.depth_m, pixel.x(), pixel.y());
  if (z_seen <= 0.0 || std::abs(in_b.z() - z_seen) > occlusion_tolerance * in_b.z()) {
    out.status = PredictionStatus::kOccluded;
    return out;
  }
  const double focal_ratio = (b.camera.fx + b.camera.fy) / (a.camera.fx + a.camera.fy);
  out.size_in_b = keypoint.size * focal_ratio * z_a / in_b.z();
  // A point one radius along the keypoint's direction, at A's depth, seen from B.
  const double radius = std::max(1.0, 0.5 * keypoint.size);
  const double angle_rad = keypoint.angle * kPi / 180.0;
  const Eigen::Vector3d along_in_a = a.camera.Unproject(keypoint.pt.x + radius * std::cos(angle_rad),
                                                        keypoint.pt.y + radius * std::sin(angle_rad), z_a);
  Eigen::Vector2d along_pixel;
  if (!b.camera.Project(b_from_world * (a.world_from_camera * along_in_a), &along_pixel)) {
    out.status = PredictionStatus::kBehindCamera;
    return out;
  }
  const Eigen::Vector2d direction = along_pixel - pixel;
  out.angle_in_b_deg = WrapDeg(std::atan2(direction.y(), direction.x()) * 180.0 / kPi);
  out.status = PredictionStatus::kVisible;
  return out;
}

namespace {

// B's keypoints by the cell of side `cell_px` that holds them.
class KeypointGrid {
 public:
  KeypointGrid(const std::vector<cv::KeyPoint>& keypoints, double cell_px) : cell_px_(cell_px) {
    for (size_t i = 0; i < keypoints.size(); ++i) {
      cells_.push_back({Cell(keypoints[i].pt.x), Cell(keypoints[i].pt.y), static_cast<int>(i)});
    }
    std::sort(cells_.begin(), cells_.end());
  }
  // Calls visit(index) for the keypoints in the 3 x 3 cells around (x, y).
  template <typename Visit>
  void Near(double x, double y, Visit visit) const {
    const long cx = Cell(x), cy = Cell(y);
    for (long gx = cx - 1; gx <= cx + 1; ++gx) {
      for (long gy = cy - 1; gy <= cy + 1; ++gy) {
        auto it = std::lower_bound(cells_.begin(), cells_.end(), std::make_tuple(gx, gy, -1));
        for (; it != cells_.end() && std::get<0>(*it) == gx && std::get<1>(*it) == gy; ++it) visit(std::get<2>(*it));
      }
    }
  }

 private:
  long Cell(double v) const { return static_cast<long>(std::floor(v / cell_px_)); }
  double cell_px_;
  std::vector<std::tuple<long, long, int>> cells_;
};

bool PassesShape(const cv::KeyPoint& candidate, const PredictedKeypoint& predicted,
                 const CorrespondenceOptions& options) {
  const double ratio = candidate.size / predicted.size_in_b;
  return ratio <= options.max_scale_ratio && ratio >= 1.0 / options.max_scale_ratio &&
         AngleDifferenceDeg(candidate.angle, predicted.angle_in_b_deg) <= options.max_angle_deg;
}

}  // namespace

std::vector<KeypointMatch> MatchKeypoints(const std::vector<cv::KeyPoint>& keypoints_a, const ViewGeometry& a,
                                          const std::vector<cv::KeyPoint>& keypoints_b, const ViewGeometry& b,
                                          const CorrespondenceOptions& options) {
  const KeypointGrid grid(keypoints_b, options.max_offset_px);
  std::vector<KeypointMatch> candidates;
  for (size_t i = 0; i < keypoints_a.size(); ++i) {
    const PredictedKeypoint predicted = PredictKeypoint(keypoints_a[i], a, b, options.occlusion_tolerance);
    if (predicted.status != PredictionStatus::kVisible) continue;
    KeypointMatch best;
    best.offset_px = static_cast<float>(options.max_offset_px) * 2.0f;
    grid.Near(predicted.pt_in_b.x, predicted.pt_in_b.y, [&](int j) {
      const float offset = static_cast<float>(cv::norm(keypoints_b[j].pt - predicted.pt_in_b));
      if (offset > options.max_offset_px || !PassesShape(keypoints_b[j], predicted, options)) return;
      if (offset < best.offset_px || (offset == best.offset_px && j < best.index_b)) {
        best.index_b = j;
        best.offset_px = offset;
      }
    });
    if (best.offset_px > options.max_offset_px) continue;
    best.index_a = static_cast<int>(i);
    best.point_in_world = predicted.point_in_world.cast<float>();
    candidates.push_back(best);
  }
  // One B keypoint per A keypoint: the nearest pairs keep theirs.
  std::stable_sort(candidates.begin(), candidates.end(),
                   [](const KeypointMatch& x, const KeypointMatch& y) { return x.offset_px < y.offset_px; });
  std::vector<bool> taken(keypoints_b.size(), false);
  std::vector<KeypointMatch> matches;
  for (const KeypointMatch& m : candidates) {
    if (taken[m.index_b]) continue;
    taken[m.index_b] = true;
    matches.push_back(m);
  }
  std::sort(matches.begin(), matches.end(),
            [](const KeypointMatch& x, const KeypointMatch& y) { return x.index_a < y.index_a; });
  return matches;
}

}  // namespace duskmap
