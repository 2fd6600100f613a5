// How a dataset is read: whether unusable frames stop the read or are skipped,
// and where skipped frames are reported.
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

  void Check() const;
};

// Either throws InputError(message) or, when options.skip_bad_frames, logs it.
void ReportBadFrame(const DatasetReadOptions& options, const std::string& message);

}  // namespace duskmap
