// libFuzzer target: the pose-file parser never throws on content; every pose
// it returns must be finite with strictly increasing timestamps.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "slam/datasets/poses_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const duskmap::PosesFile file =
      duskmap::ParsePosesText(std::string(reinterpret_cast<const char*>(data), size));
  for (size_t i = 0; i < file.poses.size(); ++i) {
    if (!file.poses[i].map_from_frame.IsFinite()) std::abort();
    if (i > 0 && !(file.poses[i].stamp_s > file.poses[i - 1].stamp_s)) std::abort();
  }
  return 0;
}
