// Classifies a localization session's re-localizations against ground truth
// (slam/eval): the map frame is aligned to the ground-truth frame (at the
// matched node by default, or per connected session group from all its
// nodes), and each re-localized frame's corrected pose is compared with its
// true pose. A map built from drifting odometry is only locally consistent
// with the ground truth, so the whole-map alignment also counts the map's own
// drift as re-localization error (measured: several degrees at the far end
// of a 30-frame single-session map).
#pragma once

#include <optional>
#include <vector>

#include "slam/core/rigid3.h"
#include "slam/engine/localization_record.h"
#include "slam/eval/gap_metrics.h"
#include "slam/eval/relocalization_metrics.h"
#include "slam/map/map.h"

namespace duskmap {

enum class TruthAlignment {
  // truth_from_map = truth_from_node * map_from_node^-1 at the matched node:
  // judges the re-localization itself, not the map's odometry drift far away.
  kMatchedNode,
  // One SE(3) alignment per connected session group from all its nodes.
  kWholeMap,
};

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
                                         std::vector<LocalizationRecord>* records,
                                         TruthAlignment alignment = TruthAlignment::kMatchedNode);

}  // namespace duskmap
