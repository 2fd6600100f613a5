// Correctness of a re-localization: its corrected camera pose, expressed in
// the ground-truth frame through the map-to-ground-truth alignment, is
// compared with the true camera pose at three thresholds (0.25 m/2 deg,
// 0.5 m/5 deg, 5 m/10 deg, as in common long-term localization benchmarks);
// by default "correct" means within 0.5 m and 5 deg. A re-localization
// outside the chosen threshold is wrong, never silently a success.
#pragma once

#include <array>
#include <vector>

#include "slam/core/rigid3.h"
#include "slam/eval/alignment.h"

namespace duskmap {

struct PoseThreshold {
  double max_translation_m = 0.5;  // metres
  double max_rotation_deg = 5.0;   // degrees
};

inline constexpr int kNumPoseThresholds = 3;

struct RelocalizationMetricsOptions {
  // Increasing thresholds, reported together.
  std::array<PoseThreshold, kNumPoseThresholds> thresholds = {
      PoseThreshold{0.25, 2.0}, PoseThreshold{0.5, 5.0}, PoseThreshold{5.0, 10.0}};
  int correct_threshold_index = 1;  // which threshold defines "correct" (0..2)

  void Check() const;
};

struct PoseError {
  double translation_m = 0.0;  // metres
  double rotation_deg = 0.0;   // degrees, in [0, 180]
};

// Error of `estimated` against `truth` (both target_from_camera in one frame).
PoseError ComputePoseError(const Rigid3d& estimated, const Rigid3d& truth);

struct RelocalizationCheck {
  PoseError error;
  std::array<bool, kNumPoseThresholds> within{};  // per threshold of the options
  bool correct = false;  // within the threshold options.correct_threshold_index
};

// truth_from_map aligns the map frame to the ground-truth frame (see
// AlignMapToTruth); map_from_camera is the engine's corrected camera pose.
RelocalizationCheck ClassifyRelocalization(const Rigid3d& truth_from_map,
                                           const Rigid3d& map_from_camera,
                                           const Rigid3d& truth_from_camera,
                                           const RelocalizationMetricsOptions& options);

// SE(3) alignment of the map to the ground truth from the camera poses of
// map nodes and their ground truth (paired by index). The rotation is the
// chordal mean of truth_R_i * map_R_i^T (projected onto SO(3) by SVD), so it
// is well determined even for a straight route where positions alone leave
// the roll about the path free; the translation is then the mean of
// truth_t_i - R * map_t_i. Throws InputError for a size mismatch or no pose.
Rigid3d AlignMapToTruth(const std::vector<Rigid3d>& map_from_node_camera,
                        const std::vector<Rigid3d>& truth_from_node_camera);

struct RelocalizationSummary {
  int num_frames = 0;
  int num_relocalized = 0;
  std::array<int, kNumPoseThresholds> num_within{};  // re-localizations within each threshold
  int num_correct = 0;  // within the default threshold
  int num_wrong = 0;    // re-localized but outside the default threshold
  double relocalized_pct = 0.0;  // 100 * num_relocalized / num_frames
  double correct_pct = 0.0;      // 100 * num_correct / num_frames
};

// Accumulates the checks of one session's re-localized frames.
RelocalizationSummary SummarizeRelocalizations(int num_frames,
                                               const std::vector<RelocalizationCheck>& checks);

}  // namespace duskmap
