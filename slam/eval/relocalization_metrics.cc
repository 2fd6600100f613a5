#include "slam/eval/relocalization_metrics.h"

#include <cmath>

#include <Eigen/SVD>

#include "slam/core/check.h"

namespace duskmap {

void RelocalizationMetricsOptions::Check() const {
  for (int i = 0; i < kNumPoseThresholds; ++i) {
    SLAM_THROW_IF_NOT(ConfigError, thresholds[i].max_translation_m > 0.0 &&
                                       thresholds[i].max_rotation_deg > 0.0)
        << "RelocalizationMetricsOptions.thresholds[" << i << "]: limits must be > 0";
  }
  SLAM_THROW_IF_NOT(ConfigError,
                    correct_threshold_index >= 0 && correct_threshold_index < kNumPoseThresholds)
      << "RelocalizationMetricsOptions.correct_threshold_index: must be in [0, "
      << kNumPoseThresholds - 1 << "], got " << correct_threshold_index;
}

PoseError ComputePoseError(const Rigid3d& estimated, const Rigid3d& truth) {
  PoseError error;
  error.translation_m = (estimated.translation - truth.translation).norm();
  error.rotation_deg = RotationAngleRad(estimated.rotation, truth.rotation) * 180.0 / M_PI;
  return error;
}

RelocalizationCheck ClassifyRelocalization(const Rigid3d& truth_from_map,
                                           const Rigid3d& map_from_camera,
                                           const Rigid3d& truth_from_camera,
                                           const RelocalizationMetricsOptions& options) {
  options.Check();
  RelocalizationCheck check;
  check.error = ComputePoseError(truth_from_map * map_from_camera, truth_from_camera);
  for (int i = 0; i < kNumPoseThresholds; ++i) {
    check.within[i] = check.error.translation_m <= options.thresholds[i].max_translation_m &&
                      check.error.rotation_deg <= options.thresholds[i].max_rotation_deg;
  }
  check.correct = check.within[options.correct_threshold_index];
  return check;
}

Rigid3d AlignMapToTruth(const std::vector<Rigid3d>& map_from_node_camera,
                        const std::vector<Rigid3d>& truth_from_node_camera) {
  SLAM_THROW_IF_NOT(InputError, map_from_node_camera.size() == truth_from_node_camera.size())
      << "AlignMapToTruth: " << map_from_node_camera.size() << " map poses but "
      << truth_from_node_camera.size() << " ground-truth poses";
  SLAM_THROW_IF_NOT(InputError, !map_from_node_camera.empty()) << "AlignMapToTruth: no pose";
  Eigen::Matrix3d sum = Eigen::Matrix3d::Zero();
  for (size_t i = 0; i < map_from_node_camera.size(); ++i) {
    sum += truth_from_node_camera[i].rotation.toRotationMatrix() *
           map_from_node_camera[i].rotation.toRotationMatrix().transpose();
  }
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(sum, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d sign = Eigen::Matrix3d::Identity();
  if (svd.matrixU().determinant() * svd.matrixV().determinant() < 0.0) sign(2, 2) = -1.0;
  const Eigen::Matrix3d rotation = svd.matrixU() * sign * svd.matrixV().transpose();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < map_from_node_camera.size(); ++i) {
    translation += truth_from_node_camera[i].translation - rotation * map_from_node_camera[i].translation;
  }
  return Rigid3d(rotation, translation / static_cast<double>(map_from_node_camera.size()));
}

RelocalizationSummary SummarizeRelocalizations(int num_frames,
                                               const std::vector<RelocalizationCheck>& checks) {
  SLAM_THROW_IF_NOT(InputError, num_frames >= static_cast<int>(checks.size()))
      << "SummarizeRelocalizations: " << checks.size() << " re-localizations in " << num_frames
      << " frames";
  RelocalizationSummary summary;
  summary.num_frames = num_frames;
  summary.num_relocalized = static_cast<int>(checks.size());
  for (const RelocalizationCheck& check : checks) {
    for (int i = 0; i < kNumPoseThresholds; ++i) summary.num_within[i] += check.within[i];
    if (check.correct) {
      ++summary.num_correct;
    } else {
      ++summary.num_wrong;
    }
  }
  if (num_frames > 0) {
    summary.relocalized_pct = 100.0 * summary.num_relocalized / num_frames;
    summary.correct_pct = 100.0 * summary.num_correct / num_frames;
  }
  return summary;
}

}  // namespace duskmap
