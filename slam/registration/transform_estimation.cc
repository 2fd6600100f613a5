#include "slam/registration/transform_estimation.h"

#include <cmath>

#include "slam/core/check.h"
#include "slam/core/timer.h"
#include "slam/registration/transform_estimation_json.h"

namespace duskmap {
namespace {

// 3D-2D correspondences of one pass, restricted to finite map points and
// finite keypoints on both sides.
struct Correspondences {
  std::vector<cv::DMatch> matches;
  std::vector<Eigen::Vector3d> points_in_node;
  std::vector<Eigen::Vector2d> pixels_in_query;
};

Eigen::Vector2d Pixel(const cv::KeyPoint& keypoint) {
  return Eigen::Vector2d(keypoint.pt.x, keypoint.pt.y);
}

Correspondences Collect(const std::vector<cv::DMatch>& matches, const FrameFeatures& map_node,
                        const FrameFeatures& query) {
  Correspondences c;
  for (const cv::DMatch& m : matches) {
    SLAM_CHECK(m.queryIdx >= 0 && m.queryIdx < static_cast<int>(query.size()));
    SLAM_CHECK(m.trainIdx >= 0 && m.trainIdx < static_cast<int>(map_node.size()));
    if (!map_node.HasPoint(m.trainIdx)) continue;
    const Eigen::Vector2d pixel = Pixel(query.keypoints[m.queryIdx]);
    if (!pixel.allFinite() || !Pixel(map_node.keypoints[m.trainIdx]).allFinite()) continue;
    c.matches.push_back(m);
    c.points_in_node.push_back(map_node.points_in_camera[m.trainIdx].cast<double>());
    c.pixels_in_query.push_back(pixel);
  }
  return c;
}

int CountPoints(const FrameFeatures& features) {
  int count = 0;
  for (size_t i = 0; i < features.points_in_camera.size(); ++i) count += features.HasPoint(i);
  return count;
}

Eigen::Vector3d QueryPoint(const FrameFeatures& query, int index) {
  if (query.points_in_camera.empty() || !query.HasPoint(index)) {
    return Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  }
  return query.points_in_camera[index].cast<double>();
}

void ValidateInputs(const RegistrationOptions& options, const FrameFeatures& map_node,
                    const PinholeCamera& map_camera, const FrameFeatures& query,
                    const PinholeCamera& query_camera) {
  options.Check();
  SLAM_THROW_IF_NOT(InputError, map_camera.IsValid())
      << "registration: invalid map node camera (size and focal lengths must be > 0)";
  SLAM_THROW_IF_NOT(InputError, query_camera.IsValid())
      << "registration: invalid query camera (size and focal lengths must be > 0)";
  CheckFeatures(map_node, "map node features");
  CheckFeatures(query, "query features");
  SLAM_THROW_IF_NOT(InputError,
                    map_node.empty() || map_node.points_in_camera.size() == map_node.size())
      << "map node features: " << map_node.points_in_camera.size() << " 3D points for "
      << map_node.size() << " keypoints (one per keypoint, NaN when missing)";
  CheckComparable(map_node, query);
}

// One PnP RANSAC pass over a pass's correspondences.
PnpResult RunPnp(const RegistrationOptions& options, const Correspondences& c,
                 const PinholeCamera& query_camera) {
  return EstimatePnpRansac(options.pnp, c.points_in_node, c.pixels_in_query, query_camera);
}

// Steps 4-5 once a PnP estimate with enough inliers exists.
void RefineAndFinish(const RegistrationOptions& options, const FrameFeatures& map_node,
                     const PinholeCamera& map_camera, const FrameFeatures& query,
                     const PinholeCamera& query_camera, const Correspondences& c,
                     const PnpResult& pnp, RegistrationResult* result) {
  std::vector<cv::DMatch> inliers;
  for (int k : pnp.inliers) inliers.push_back(c.matches[k]);
  Rigid3d query_from_node = pnp.camera_from_points;

  if (options.bundle_adjustment.enabled) {
    Stopwatch watch;
    std::vector<BundleAdjustmentCorrespondence> ba;
    for (const cv::DMatch& m : inliers) {
      const cv::KeyPoint& node_kp = map_node.keypoints[m.trainIdx];
      ba.push_back({map_node.points_in_camera[m.trainIdx].cast<double>(), Pixel(node_kp),
                    Pixel(query.keypoints[m.queryIdx]), QueryPoint(query, m.queryIdx)});
    }
    const BundleAdjustmentResult refined = RefineTwoViewBundleAdjustment(
        options.bundle_adjustment, ba, map_camera, query_camera, query_from_node);
    result->timings.bundle_adjustment_ms = watch.ElapsedMs();
    if (!refined.success) {
      result->status = RegistrationStatus::kBundleAdjustmentFailed;
      return;
    }
    std::vector<cv::DMatch> kept;
    for (int k : refined.inliers) kept.push_back(inliers[k]);
    inliers = std::move(kept);
    query_from_node = refined.query_from_node;
    if (static_cast<int>(inliers.size()) < options.min_inliers) {
      result->num_inliers = static_cast<int>(inliers.size());
      result->status = RegistrationStatus::kBundleAdjustmentTooFewInliers;
      return;
    }
  }

  Stopwatch watch;
  const Rigid3d node_from_query = query_from_node.Inverse();
  std::vector<InlierCorrespondence> for_information;
  for (const cv::DMatch& m : inliers) {
    for_information.push_back({map_node.points_in_camera[m.trainIdx].cast<double>(),
                               Pixel(query.keypoints[m.queryIdx]),
                               QueryPoint(query, m.queryIdx)});
  }
  const LinkCovariance covariance = ComputeLinkInformation(
      options.information, for_information, query_camera, node_from_query);
  result->timings.information_ms = watch.ElapsedMs();
  result->num_inliers = static_cast<int>(inliers.size());
  result->inlier_ratio = c.matches.empty() ? 0.0 : double(inliers.size()) / c.matches.size();
  if (options.information.max_linear_variance_m2 > 0.0 &&
      covariance.linear_variance_m2 > options.information.max_linear_variance_m2) {
    result->status = RegistrationStatus::kVarianceTooHigh;
    return;
  }
  result->status = RegistrationStatus::kAccepted;
  result->node_from_query = node_from_query;
  result->inlier_matches = std::move(inliers);
  result->linear_variance_m2 = covariance.linear_variance_m2;
  result->angular_variance = covariance.angular_variance;
  result->information = covariance.information;
}

// Step 3: guided matching around the projections under the first estimate,
// then PnP RANSAC again. Returns false, with result->status set, on rejection.
bool RunSecondPass(const RegistrationOptions& options, const FrameFeatures& map_node,
                   const FrameFeatures& query, const PinholeCamera& query_camera,
                   const Rigid3d& query_from_node, Correspondences* second, PnpResult* pnp,
                   RegistrationResult* result) {
  const Stopwatch watch;
  result->second_pass_ran = true;
  *second = Collect(MatchInProjectionWindow(options.GuidedMatching(), map_node, query,
                                            query_camera, query_from_node),
                    map_node, query);
  result->matches_second_pass = static_cast<int>(second->matches.size());
  if (result->matches_second_pass < options.min_inliers) {
    result->timings.second_pass_ms = watch.ElapsedMs();
    result->status = RegistrationStatus::kSecondPassTooFewMatches;
    return false;
  }
  *pnp = RunPnp(options, *second, query_camera);
  result->timings.second_pass_ms = watch.ElapsedMs();
  result->inliers_second_pass = static_cast<int>(pnp->inliers.size());
  result->ransac_trials += pnp->num_trials;
  if (!pnp->success) {
    result->status = RegistrationStatus::kSecondPassPnpFailed;
    return false;
  }
  if (result->inliers_second_pass < options.min_inliers) {
    result->num_inliers = result->inliers_second_pass;
    result->status = RegistrationStatus::kSecondPassTooFewInliers;
    return false;
  }
  return true;
}

}  // namespace

void RegistrationOptions::Check() const {
  SLAM_THROW_IF_NOT(ConfigError, min_inliers >= 6)
      << "RegistrationOptions.min_inliers: must be >= 6, got " << min_inliers;
  SLAM_THROW_IF_NOT(ConfigError, guess_window_px > 0.0 && std::isfinite(guess_window_px))
      << "RegistrationOptions.guess_window_px: must be finite and > 0, got " << guess_window_px;
  matching.Check();
  pnp.Check();
  bundle_adjustment.Check();
  information.Check();
}

GuidedMatchingOptions RegistrationOptions::GuidedMatching() const {
  GuidedMatchingOptions guided;
  guided.window_px = guess_window_px;
  guided.float_ratio = matching.float_ratio;
  guided.binary_ratio = matching.binary_ratio;
  return guided;
}

const char* RegistrationStatusName(RegistrationStatus status) { return JsonEnumName(status); }

RegistrationResult EstimateTransform(const RegistrationOptions& options,
                                     const FrameFeatures& map_node,
                                     const PinholeCamera& map_camera,
                                     const FrameFeatures& query,
                                     const PinholeCamera& query_camera,
                                     const FeatureMatcher* matcher) {
  ValidateInputs(options, map_node, map_camera, query, query_camera);
  const Stopwatch total;
  RegistrationResult result;
  auto finish = [&]() {
    result.timings.total_ms = total.ElapsedMs();
    return result;
  };
  if (CountPoints(map_node) < options.min_inliers ||
      static_cast<int>(query.size()) < options.min_inliers) {
    result.status = RegistrationStatus::kNoFeatures;
    return finish();
  }

  // 1. Global matching.
  Stopwatch watch;
  const NndrMatcher nndr(options.matching);
  const FeatureMatcher& global_matcher = matcher ? *matcher : nndr;
  const Correspondences first = Collect(
      global_matcher.Match(query, cv::Size(query_camera.width, query_camera.height), map_node,
                           cv::Size(map_camera.width, map_camera.height)),
      map_node, query);
  result.timings.matching_ms = watch.ElapsedMs();
  result.matches_first_pass = static_cast<int>(first.matches.size());
  if (result.matches_first_pass < options.min_inliers) {
    result.status = RegistrationStatus::kTooFewMatches;
    return finish();
  }

  // 2. PnP RANSAC.
  watch.Restart();
  const PnpResult first_pnp = RunPnp(options, first, query_camera);
  result.timings.pnp_ms = watch.ElapsedMs();
  result.inliers_first_pass = static_cast<int>(first_pnp.inliers.size());
  result.ransac_trials = first_pnp.num_trials;
  if (!first_pnp.success) {
    result.status = RegistrationStatus::kPnpFailed;
    return finish();
  }
  if (result.inliers_first_pass < options.min_inliers) {
    result.num_inliers = result.inliers_first_pass;
    result.status = RegistrationStatus::kTooFewInliers;
    return finish();
  }

  // 3. Second pass, guided by the first estimate.
  const bool run_second =
      options.second_pass && (matcher == nullptr || options.second_pass_with_external_matcher);
  if (!run_second) {
    RefineAndFinish(options, map_node, map_camera, query, query_camera, first, first_pnp,
                    &result);
    return finish();
  }
  Correspondences second;
  PnpResult second_pnp;
  if (!RunSecondPass(options, map_node, query, query_camera, first_pnp.camera_from_points,
                     &second, &second_pnp, &result)) {
    return finish();
  }
  RefineAndFinish(options, map_node, map_camera, query, query_camera, second, second_pnp,
                  &result);
  return finish();
}

void RejectLongerThan(double max_translation_m, RegistrationResult* result) {
  if (result->accepted() && !(result->node_from_query.translation.norm() <= max_translation_m)) {
    result->status = RegistrationStatus::kTranslationTooLong;
  }
}

}  // namespace duskmap
