#include "slam/datasets/dataset_read_options.h"

#include "slam/core/check.h"

namespace duskmap {

void SkipLog::Add(const std::string& message) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (seen_.insert(message).second) ordered_.push_back(message);
}

int64_t SkipLog::count() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return static_cast<int64_t>(ordered_.size());
}

std::vector<std::string> SkipLog::messages() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return ordered_;
}

void DatasetReadOptions::Check() const {
  SLAM_THROW_IF_NOT(ConfigError, !skip_bad_frames || skip_log != nullptr)
      << "DatasetReadOptions.skip_log: required when skip_bad_frames is true "
         "(skipped frames must be reported)";
}

void ReportBadFrame(const DatasetReadOptions& options, const std::string& message) {
  if (!options.skip_bad_frames) throw InputError(message);
  options.skip_log->Add(message);
}

}  // namespace duskmap
