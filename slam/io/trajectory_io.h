// Trajectories in the TUM RGB-D text format, one pose per line:
//   timestamp tx ty tz qx qy qz qw
// ('#' starts a comment line). Used for groundtruth.txt, odometry.txt and the
// trajectories the engine writes.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "slam/core/rigid3.h"

namespace duskmap {

struct TrajectoryPose {
  double timestamp_s = 0.0;
  Rigid3d pose;  // target_from_source as named by the file (e.g. world_from_camera)
};
// Former name, kept for callers; the type is named TrajectoryPose so that it
// does not collide (ODR) with datasets' own StampedPose in poses_file.h.
using StampedPose = TrajectoryPose;

// Reads a TUM trajectory; throws InputError "<path>:<line>: <problem>" on a
// missing file, malformed line, non-finite value or decreasing timestamp.
std::vector<TrajectoryPose> ReadTrajectory(const std::string& path);

// Writes a TUM trajectory (9 significant digits for positions, timestamps with
// microseconds); throws InputError when the file cannot be written.
void WriteTrajectory(const std::string& path, const std::vector<TrajectoryPose>& poses,
                     const std::string& header_comment = "");

// The pose at timestamp_s: linear/slerp interpolation between the two
// bracketing poses when both are within max_gap_s of it, the nearest pose when
// it is within max_gap_s, otherwise nullopt. `poses` must be sorted by time.
std::optional<Rigid3d> InterpolatePose(const std::vector<TrajectoryPose>& poses, double timestamp_s,
                                       double max_gap_s);

}  // namespace duskmap
