// RTAB-Map pose files (`rtabmap-export --poses_format 11`, the image release's
// device_poses.txt / camera_poses.txt): an optional `#...` header, then one line
// `stamp x y z qx qy qz qw id` per pose (format 10 and TUM lines without `id`
// are accepted too). Poses map the pose's frame into the file's map frame.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "slam/core/rigid3.h"

namespace duskmap {

struct PoseLine {
  int line = 0;            // 1-based line number in the file
  double stamp_s = 0.0;    // seconds
  std::string stamp_text;  // the stamp token as written (matches image file stems)
  int64_t id = -1;         // node id, -1 when the line has none
  Rigid3d map_from_frame;  // the pose
};

// A line that cannot be used, with its 1-based number and the problem.
struct BadPoseLine {
  int line = 0;
  std::string problem;
};

struct PosesFile {
  std::vector<PoseLine> poses;      // usable lines, in file order
  std::vector<BadPoseLine> bad_lines;  // malformed, non-finite, non-unit quaternion,
                                       // timestamp not after the previous usable line
};

// Parses the text of a pose file. Never throws on content: every unusable line
// is listed in bad_lines (the caller decides whether that is fatal).
PosesFile ParsePosesText(const std::string& text);

// Reads and parses a pose file; throws InputError when it cannot be read.
PosesFile ReadPosesFile(const std::string& path);

}  // namespace duskmap
