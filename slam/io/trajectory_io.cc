#include "slam/io/trajectory_io.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "slam/core/check.h"
#include "slam/core/input_file.h"
#include "slam/io/output_safety.h"

namespace duskmap {

std::vector<TrajectoryPose> ReadTrajectory(const std::string& path) {
  RefuseNonRegularFile(path);  // before opening: a FIFO would block
  std::ifstream in(path);
  SLAM_THROW_IF_NOT(InputError, in.good()) << path << ": cannot open trajectory file";
  std::vector<TrajectoryPose> poses;
  std::string line;
  int line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    const size_t first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    std::istringstream fields(line);
    double v[8];
    for (double& x : v) {
      SLAM_THROW_IF_NOT(InputError, static_cast<bool>(fields >> x))
          << path << ":" << line_number << ": malformed pose line (expected 8 numbers)";
      SLAM_THROW_IF_NOT(InputError, std::isfinite(x))
          << path << ":" << line_number << ": non-finite value";
    }
    const Eigen::Quaterniond q(v[7], v[4], v[5], v[6]);
    SLAM_THROW_IF_NOT(InputError, q.norm() > 0.5 && q.norm() < 1.5)
        << path << ":" << line_number << ": quaternion is not unit (norm " << q.norm() << ")";
    SLAM_THROW_IF_NOT(InputError, poses.empty() || v[0] >= poses.back().timestamp_s)
        << path << ":" << line_number << ": timestamps decrease";
    poses.push_back({v[0], Rigid3d(q, Eigen::Vector3d(v[1], v[2], v[3]))});
  }
  return poses;
}

void WriteTrajectory(const std::string& path, const std::vector<TrajectoryPose>& poses,
                     const std::string& header_comment) {
  WriteFileAtomically(path, [&](std::ostream& out) {
    if (!header_comment.empty()) out << "# " << header_comment << "\n";
    out << "# timestamp tx ty tz qx qy qz qw\n";
    for (const TrajectoryPose& p : poses) {
      const Eigen::Quaterniond& q = p.pose.rotation;
      const Eigen::Vector3d& t = p.pose.translation;
      out << std::fixed << std::setprecision(6) << p.timestamp_s << std::setprecision(9) << " "
          << t.x() << " " << t.y() << " " << t.z() << " " << q.x() << " " << q.y() << " "
          << q.z() << " " << q.w() << "\n";
    }
  });
}

std::optional<Rigid3d> InterpolatePose(const std::vector<TrajectoryPose>& poses, double timestamp_s,
                                       double max_gap_s) {
  if (poses.empty()) return std::nullopt;
  const auto after = std::lower_bound(
      poses.begin(), poses.end(), timestamp_s,
      [](const TrajectoryPose& p, double t) { return p.timestamp_s < t; });
  if (after != poses.end() && after->timestamp_s == timestamp_s) return after->pose;
  if (after != poses.end() && after != poses.begin()) {
    const TrajectoryPose& a = *(after - 1);
    const TrajectoryPose& b = *after;
    if (timestamp_s - a.timestamp_s <= max_gap_s && b.timestamp_s - timestamp_s <= max_gap_s) {
      const double s = (timestamp_s - a.timestamp_s) / (b.timestamp_s - a.timestamp_s);
      return Rigid3d(a.pose.rotation.slerp(s, b.pose.rotation),
                     (1.0 - s) * a.pose.translation + s * b.pose.translation);
    }
  }
  const TrajectoryPose* nearest = nullptr;
  if (after != poses.end()) nearest = &*after;
  if (after != poses.begin()) {
    const TrajectoryPose& before = *(after - 1);
    if (nearest == nullptr ||
        timestamp_s - before.timestamp_s < nearest->timestamp_s - timestamp_s) {
      nearest = &before;
    }
  }
  if (std::abs(nearest->timestamp_s - timestamp_s) <= max_gap_s) return nearest->pose;
  return std::nullopt;
}

}  // namespace duskmap
