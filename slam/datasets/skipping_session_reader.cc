#include "slam/datasets/skipping_session_reader.h"

#include "slam/core/check.h"

namespace duskmap {

SkippingSessionReader::SkippingSessionReader(std::unique_ptr<SessionReader> inner,
                                             std::shared_ptr<SkipLog> log)
    : inner_(std::move(inner)), log_(std::move(log)) {
  SLAM_CHECK(inner_ != nullptr && log_ != nullptr);
}

std::optional<RgbdFrame> SkippingSessionReader::Next() {
  int64_t failures = 0;
  while (true) {
    try {
      return inner_->Next();
    } catch (const InputError& e) {
      if (++failures > inner_->info().num_frames + 1) throw;
      log_->Add(e.what());
    }
  }
}

SkippingDatasetReader::SkippingDatasetReader(std::unique_ptr<DatasetReader> inner,
                                             std::shared_ptr<SkipLog> log)
    : inner_(std::move(inner)), log_(std::move(log)) {
  SLAM_CHECK(inner_ != nullptr && log_ != nullptr);
}

std::unique_ptr<SessionReader> SkippingDatasetReader::OpenSession(const std::string& name) const {
  return std::make_unique<SkippingSessionReader>(inner_->OpenSession(name), log_);
}

}  // namespace duskmap
