// Transformation estimation between a map node and a query frame (spec 6):
//  1. global NNDR matching (or a caller-supplied FeatureMatcher, e.g. SuperGlue);
//  2. PnP RANSAC on map 3D points / query 2D keypoints;
//  3. second pass: matching inside a window around the projections of the map
//     points under the first estimate, then PnP RANSAC again (Reg/RepeatOnce);
//     if it fails the registration fails (no fall-back to the first pass);
//  4. two-view bundle adjustment on the inliers;
//  5. the link covariance / information (6.6).
// Each step that can reject does so with its own status; the result never
// carries a non-finite pose.
#pragma once

#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

#include "slam/core/camera.h"
#include "slam/core/graph_types.h"
#include "slam/core/rigid3.h"
#include "slam/features/feature_matcher.h"
#include "slam/features/frame_features.h"
#include "slam/registration/bundle_adjustment.h"
#include "slam/registration/guided_matching.h"
#include "slam/registration/link_information.h"
#include "slam/registration/nndr_matcher.h"
#include "slam/registration/pnp_ransac.h"

namespace duskmap {

struct RegistrationOptions {
  int min_inliers = 20;  // Vis/MinInliers: fewest inliers to accept (>= 6)
  NndrMatcherOptions matching;
  PnpRansacOptions pnp;
  bool second_pass = true;  // Reg/RepeatOnce
  // Window of the second pass (Vis/CorGuessWinSize, px); its ratios follow `matching`.
  double guess_window_px = 40.0;
  // With a caller-supplied (learned) matcher the second pass is skipped
  // unless this is set (the reference always ran it, with brute-force NNDR).
  bool second_pass_with_external_matcher = false;
  LocalBundleAdjustmentOptions bundle_adjustment;
  LinkInformationOptions information;

  void Check() const;
  GuidedMatchingOptions GuidedMatching() const;
};

enum class RegistrationStatus {
  kAccepted,
  kNoFeatures,               // fewer than min_inliers map 3D points or query keypoints
  kTooFewMatches,            // first-pass correspondences < min_inliers
  kPnpFailed,                // RANSAC found no model
  kTooFewInliers,            // first-pass PnP inliers < min_inliers
  kSecondPassTooFewMatches,  // guided correspondences < min_inliers
  kSecondPassPnpFailed,      // RANSAC found no model on the guided correspondences
  kSecondPassTooFewInliers,  // guided PnP inliers < min_inliers
  kBundleAdjustmentFailed,   // the solver failed or returned a non-finite pose
  kBundleAdjustmentTooFewInliers,  // inliers left after outlier removal < min_inliers
  kVarianceTooHigh,          // linear variance above information.max_linear_variance_m2
  // Set by RejectLongerThan, not by EstimateTransform: an accepted transform
  // whose translation is longer than the link may be.
  kTranslationTooLong,
};

const char* RegistrationStatusName(RegistrationStatus status);

struct RegistrationTimings {
  double matching_ms = 0.0;
  double pnp_ms = 0.0;
  double second_pass_ms = 0.0;  // guided matching + second PnP
  double bundle_adjustment_ms = 0.0;
  double information_ms = 0.0;
  double total_ms = 0.0;
};

struct RegistrationResult {
  RegistrationStatus status = RegistrationStatus::kNoFeatures;
  // Pose of the query camera in the map node's camera frame
  // (x_in_node = node_from_query * x_in_query); identity unless accepted.
  Rigid3d node_from_query;
  int num_inliers = 0;        // final inliers
  double inlier_ratio = 0.0;  // final inliers / correspondences of the last pass
  int matches_first_pass = 0;   // correspondences with a map 3D point, first pass
  int inliers_first_pass = 0;
  int matches_second_pass = 0;  // 0 when the second pass did not run
  int inliers_second_pass = 0;
  bool second_pass_ran = false;
  int ransac_trials = 0;        // minimal samples drawn, both passes
  // Final inliers: queryIdx into the query features, trainIdx into the map node's.
  std::vector<cv::DMatch> inlier_matches;
  double linear_variance_m2 = 0.0;
  double angular_variance = 0.0;  // rad^2
  Information6d information = Information6d::Zero();  // (x, y, z, roll, pitch, yaw)
  RegistrationTimings timings;

  bool accepted() const { return status == RegistrationStatus::kAccepted; }
};

// map_node: features with 3D points in the node's camera frame (NaN where no
// depth); query: features, 3D points optional (empty or NaN). Throws
// InputError for inconsistent inputs (descriptor rows vs keypoints, float vs
// binary, widths, invalid cameras); every other failure is a status.
// matcher == nullptr uses the NNDR matcher built from options.matching.
RegistrationResult EstimateTransform(const RegistrationOptions& options,
                                     const FrameFeatures& map_node,
                                     const PinholeCamera& map_camera,
                                     const FrameFeatures& query,
                                     const PinholeCamera& query_camera,
                                     const FeatureMatcher* matcher = nullptr);

// An accepted result whose translation |t| exceeds max_translation_m becomes
// kTranslationTooLong (node_from_query kept, for the records): a proximity
// link must be no longer than RGBD/ProximityPathFilteringRadius (spec §5.4,
// §6.7). Other results are left as they are.
void RejectLongerThan(double max_translation_m, RegistrationResult* result);

}  // namespace duskmap
