// Least-squares alignment of two corresponding point sets (Umeyama 1991,
// "Least-squares estimation of transformation parameters between two point
// patterns"): finds target_from_source (and optionally a scale) minimising
// sum |target_i - (s * R * source_i + t)|^2. Used to express an estimated
// trajectory or map in the ground-truth frame before measuring errors.
#pragma once

#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "slam/core/rigid3.h"

namespace duskmap {

struct AlignmentOptions {
  bool estimate_scale = false;  // true: Sim(3) alignment; false: SE(3) (scale fixed to 1)
  size_t min_points = 3;        // fewest correspondences accepted (>= 3)

  void Check() const;
};

struct AlignmentResult {
  Rigid3d target_from_source;  // rotation and translation of the alignment
  double scale = 1.0;          // s in target = s * R * source + t (1 for SE(3))
  size_t num_points = 0;       // correspondences used
  double rmse_m = 0.0;         // RMS of the residual distances after alignment, metres

  // Maps a point of the source frame into the target frame (with the scale).
  Eigen::Vector3d Apply(const Eigen::Vector3d& x_in_source) const {
    return scale * (target_from_source.rotation * x_in_source) +
           target_from_source.translation;
  }
};

// Throws InputError when the sets differ in size, hold fewer than
// options.min_points points, contain non-finite values or are degenerate
// (all points collinear, so the rotation is undetermined).
AlignmentResult AlignPoints(const std::vector<Eigen::Vector3d>& source,
                            const std::vector<Eigen::Vector3d>& target,
                            const AlignmentOptions& options = AlignmentOptions());

}  // namespace duskmap
