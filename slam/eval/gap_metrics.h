// The paper's consecutive-session metrics (paper_results.json,
// table_gap_distance): the largest distance travelled without a
// re-localization, and the share of frames re-localized within 55 cm of the
// previous re-localization (at 1 Hz and 0.55 m/s: "the frame before was
// re-localized too"). Distances are integrated along the given positions
// (odometry or ground truth: any frame, only differences are used).
//
// The share is bounded by the path: a frame that comes more than within_m
// after the one before cannot count, however well both re-localize. At 1 Hz a
// walker a little faster than 0.55 m/s loses every walking frame, so the
// bound (num_within_bound) says how much of the path the rule can count at all.
#pragma once

#include <vector>

#include <Eigen/Core>

namespace duskmap {

struct GapMetricsOptions {
  double within_m = 0.55;  // a re-localization this close (metres travelled) to the previous one counts

  void Check() const;
};

struct GapMetrics {
  // Per frame: metres travelled since the last re-localization (or since the
  // session start before the first one); 0 at a re-localized frame.
  std::vector<double> distance_since_last_m;
  double max_gap_m = 0.0;         // largest distance travelled without re-localization, metres
  double total_distance_m = 0.0;  // length of the whole path, metres
  int num_relocalized = 0;
  // Re-localized frames whose gap to the previous re-localization (or to the
  // session start, for the first) was <= within_m.
  int num_within = 0;
  double within_pct = 0.0;  // 100 * num_within / number of frames
  // num_within had every frame re-localized: the first frame and those no
  // more than within_m after the frame before (the path's bound on num_within).
  int num_within_bound = 0;
};

// positions[i] is frame i's position; relocalized[i] whether it re-localized.
// Throws InputError when the vectors differ in size or a position is not finite.
GapMetrics ComputeGapMetrics(const std::vector<Eigen::Vector3d>& positions,
                             const std::vector<bool>& relocalized,
                             const GapMetricsOptions& options = GapMetricsOptions());

}  // namespace duskmap
