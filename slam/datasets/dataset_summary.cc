#include "slam/datasets/dataset_summary.h"

#include <algorithm>
#include <limits>

#include <opencv2/core.hpp>

namespace duskmap {

SessionSummary SummarizeSession(SessionReader& session) {
  SessionSummary summary;
  summary.info = session.info();
  session.Rewind();
  double min_depth = std::numeric_limits<double>::infinity();
  double max_depth = 0.0;
  int64_t valid_pixels = 0;
  int64_t all_pixels = 0;
  while (const std::optional<RgbdFrame> frame = session.Next()) {
    if (summary.frames_read == 0) summary.first_timestamp_s = frame->timestamp_s;
    summary.last_timestamp_s = frame->timestamp_s;
    ++summary.frames_read;
    ++summary.frames_per_resolution[{frame->bgr.cols, frame->bgr.rows}];
    if (frame->world_from_camera) ++summary.frames_with_ground_truth;
    const cv::Mat valid = frame->depth_m > 0.0f;
    const int count = cv::countNonZero(valid);
    all_pixels += static_cast<int64_t>(frame->depth_m.total());
    valid_pixels += count;
    if (count == 0) continue;
    double low = 0.0, high = 0.0;
    cv::minMaxLoc(frame->depth_m, &low, &high, nullptr, nullptr, valid);
    min_depth = std::min(min_depth, low);
    max_depth = std::max(max_depth, high);
  }
  if (valid_pixels > 0) {
    summary.min_depth_m = min_depth;
    summary.max_depth_m = max_depth;
  }
  summary.valid_depth_fraction =
      all_pixels > 0 ? static_cast<double>(valid_pixels) / static_cast<double>(all_pixels) : 0.0;
  return summary;
}

}  // namespace duskmap
