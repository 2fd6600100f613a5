#include "slam/engine/localization_evaluation.h"

#include <map>

#include "slam/core/check.h"

namespace duskmap {
namespace {

// truth_from_map of the session group containing `session`, or nullopt when
// none of its nodes has ground truth.
std::optional<Rigid3d> AlignGroup(const Map& map, SessionId session) {
  std::vector<SessionId> group;
  for (const auto& g : map.ConnectedSessionGroups()) {
    if (std::find(g.begin(), g.end(), session) != g.end()) group = g;
  }
  std::vector<Rigid3d> map_poses, truth_poses;
  for (const auto& [id, node] : map.nodes()) {
    if (!node.truth_from_camera) continue;
    if (std::find(group.begin(), group.end(), node.session) == group.end()) continue;
    map_poses.push_back(node.map_from_camera());
    truth_poses.push_back(*node.truth_from_camera);
  }
  if (map_poses.empty()) return std::nullopt;
  return AlignMapToTruth(map_poses, truth_poses);
}

}  // namespace

LocalizationSummary EvaluateLocalization(const Map& map,
                                         const std::vector<std::optional<Rigid3d>>& truth_from_camera,
                                         const std::vector<Eigen::Vector3d>& odom_positions,
                                         const RelocalizationMetricsOptions& options,
                                         std::vector<LocalizationRecord>* records,
                                         TruthAlignment alignment) {
  SLAM_THROW_IF_NOT(InputError, truth_from_camera.size() == records->size() &&
                                    odom_positions.size() == records->size())
      << "EvaluateLocalization: " << records->size() << " records, " << truth_from_camera.size()
      << " ground-truth poses, " << odom_positions.size() << " odometry positions";
  LocalizationSummary summary;
  std::map<SessionId, std::optional<Rigid3d>> alignments;
  std::vector<RelocalizationCheck> checks;
  std::vector<bool> relocalized;
  int num_jumps = 0;
  for (size_t i = 0; i < records->size(); ++i) {
    LocalizationRecord& r = (*records)[i];
    r.check.reset();
    relocalized.push_back(r.relocalized);
    if (!r.relocalized) continue;
    summary.mean_inliers += r.inliers;
    if (r.jump_mm) {
      summary.mean_jump_mm += *r.jump_mm;
      ++num_jumps;
    }
    if (!truth_from_camera[i]) continue;
    std::optional<Rigid3d> truth_from_map;
    if (alignment == TruthAlignment::kMatchedNode) {
      const MapNode& node = map.node(r.matched_node);
      if (node.truth_from_camera) {
        truth_from_map = *node.truth_from_camera * node.map_from_camera().Inverse();
      }
    } else {
      if (!alignments.count(r.matched_session)) {
        alignments[r.matched_session] = AlignGroup(map, r.matched_session);
      }
      truth_from_map = alignments[r.matched_session];
    }
    if (!truth_from_map) continue;
    r.check = ClassifyRelocalization(*truth_from_map, *r.map_from_camera, *truth_from_camera[i],
                                     options);
    checks.push_back(*r.check);
    summary.evaluated = true;
  }
  const int num_relocalized = static_cast<int>(std::count(relocalized.begin(), relocalized.end(), true));
  summary.relocalization = SummarizeRelocalizations(static_cast<int>(records->size()), checks);
  // Re-localizations that could not be checked still count as re-localized.
  summary.relocalization.num_relocalized = num_relocalized;
  if (!records->empty()) {
    summary.relocalization.relocalized_pct = 100.0 * num_relocalized / records->size();
  }
  if (num_relocalized > 0) summary.mean_inliers /= num_relocalized;
  if (num_jumps > 0) summary.mean_jump_mm /= num_jumps;
  summary.gaps = ComputeGapMetrics(odom_positions, relocalized);
  return summary;
}

}  // namespace duskmap
