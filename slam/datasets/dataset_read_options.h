// How a dataset is read: whether unusable frames stop the read or are skipped,
// where skipped frames are reported, and how strictly TUM index files are read.
#pragma once

#include <cstdint>
#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <vector>

namespace duskmap {

// Collects one message per skipped frame ("<file>: node 12: <problem>").
// Shared by every session of a reader; thread-safe. The same frame skipped
// again (after Rewind) is counted once.
class SkipLog {
 public:
  void Add(const std::string& message);
  int64_t count() const;
  std::vector<std::string> messages() const;  // in the order first seen

 private:
  mutable std::mutex mutex_;
  std::set<std::string> seen_;
  std::vector<std::string> ordered_;
};

struct DatasetReadOptions {
  // When true, a frame that cannot be used (undecodable image, bad pose line,
  // calibration not matching the image, ...) is skipped and reported to
  // skip_log; when false the first such frame throws InputError.
  bool skip_bad_frames = false;
  // Receives the skipped frames; required when skip_bad_frames is true.
  std::shared_ptr<SkipLog> skip_log;
  // TUM-layout index files (formats "tum" and "synthetic"; the CLI's
  // --allow-unordered). When false, an rgb.txt/depth.txt line out of order or
  // duplicated, an rgb image without a depth image within 0.02 s, a depth
  // image nearest to two rgb images, or one used by none, is an InputError
  // naming the file and line. When true, such a folder is read leniently, as
  // real recordings that drop frames need: lines sorted by timestamp, each rgb
  // image paired with its nearest depth image, unmatched rgb images skipped
  // (see TumReadOptions in slam/io/tum_dataset.h). Other formats ignore it.
  bool allow_unordered = false;

  void Check() const;
};

// Either throws InputError(message) or, when options.skip_bad_frames, logs it.
void ReportBadFrame(const DatasetReadOptions& options, const std::string& message);

}  // namespace duskmap
