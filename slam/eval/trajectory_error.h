// Absolute trajectory error (Sturm et al. 2012, TUM RGB-D benchmark): the
// estimated positions are aligned to the ground truth (alignment.h) and the
// residual distances summarised. Poses are paired by index; the caller
// associates them (same frame, or nearest timestamps).
#pragma once

#include <vector>

#include "slam/core/rigid3.h"
#include "slam/eval/alignment.h"

namespace duskmap {

struct AteResult {
  AlignmentResult alignment;  // truth_from_estimate used to measure the errors
  size_t num_poses = 0;
  double rmse_m = 0.0;    // root mean square of the position errors, metres
  double mean_m = 0.0;    // mean position error, metres
  double median_m = 0.0;  // median position error, metres
  double max_m = 0.0;     // largest position error, metres
};

// Throws InputError when the trajectories differ in length or cannot be
// aligned (see AlignPoints).
AteResult ComputeAte(const std::vector<Rigid3d>& estimated,
                     const std::vector<Rigid3d>& ground_truth,
                     const AlignmentOptions& options = AlignmentOptions());

}  // namespace duskmap
