// Classifies a localization session's re-localizations against ground truth
// (slam/eval): the map frame of each connected group of sessions is aligned
// to the ground-truth frame from its nodes' poses and their ground truth, and
// each re-localized frame's corrected pose is compared with its true pose.
#pragma once

#include <optional>
#include <vector>

#include "slam/core/rigid3.h"
#include "slam/engine/localization_record.h"
#include "slam/eval/gap_metrics.h"
#include "slam/eval/relocalization_metrics.h"
#include "slam/map/map.h"

namespace duskmap {

struct LocalizationSummary {
  RelocalizationSummary relocalization;  // counts; wrong ones only when ground truth exists
  GapMetrics gaps;                       // along the odometry path
  bool evaluated = false;                // ground truth was available
  double mean_jump_mm = 0.0;             // over re-localizations with a jump
  double mean_inliers = 0.0;             // over re-localizations
};

// truth_from_camera[i]: ground truth of records[i]'s frame (nullopt when
// absent); odom_positions[i]: its odometry camera position. Fills
// records[i].check for re-localized frames with ground truth. Throws
// InputError when sizes differ.
LocalizationSummary EvaluateLocalization(const Map& map,
                                         const std::vector<std::optional<Rigid3d>>& truth_from_camera,
                                         const std::vector<Eigen::Vector3d>& odom_positions,
                                         const RelocalizationMetricsOptions& options,
                                         std::vector<LocalizationRecord>* records);

}  // namespace duskmap
