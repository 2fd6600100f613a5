// What a reader sees in one session, for `duskmap dataset info`: frame count,
// resolutions, depth range, time span and ground-truth coverage. Reads (and
// decodes) every frame of the session.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <utility>

#include "slam/io/dataset_reader.h"

namespace duskmap {

struct SessionSummary {
  SessionInfo info;
  int64_t frames_read = 0;
  std::map<std::pair<int, int>, int64_t> frames_per_resolution;  // (width, height) -> frames
  double min_depth_m = 0.0;           // smallest valid depth over all frames (0 when none)
  double max_depth_m = 0.0;           // largest valid depth
  double valid_depth_fraction = 0.0;  // valid depth pixels / all pixels
  double first_timestamp_s = 0.0;
  double last_timestamp_s = 0.0;
  int64_t frames_with_ground_truth = 0;
};

// Reads the session from its first frame to the end (rewinding first).
SessionSummary SummarizeSession(SessionReader& session);

}  // namespace duskmap
