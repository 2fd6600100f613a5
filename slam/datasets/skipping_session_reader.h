// Wraps any SessionReader so that a frame whose Next() throws InputError is
// skipped and logged instead of ending the read (`--skip-bad-frames`).
// Readers throw only after consuming the bad frame, so the next call moves on;
// if the wrapped reader keeps failing without progress (more consecutive
// failures than the session has frames) the error is rethrown.
#pragma once

#include <memory>

#include "slam/datasets/dataset_read_options.h"
#include "slam/io/dataset_reader.h"

namespace duskmap {

class SkippingSessionReader : public SessionReader {
 public:
  SkippingSessionReader(std::unique_ptr<SessionReader> inner, std::shared_ptr<SkipLog> log);

  const SessionInfo& info() const override { return inner_->info(); }
  std::optional<RgbdFrame> Next() override;
  void Rewind() override { inner_->Rewind(); }

 private:
  std::unique_ptr<SessionReader> inner_;
  std::shared_ptr<SkipLog> log_;
};

// Wraps every session of `inner` in a SkippingSessionReader.
class SkippingDatasetReader : public DatasetReader {
 public:
  SkippingDatasetReader(std::unique_ptr<DatasetReader> inner, std::shared_ptr<SkipLog> log);

  std::string format() const override { return inner_->format(); }
  std::vector<SessionInfo> Sessions() const override { return inner_->Sessions(); }
  std::unique_ptr<SessionReader> OpenSession(const std::string& name) const override;

 private:
  std::unique_ptr<DatasetReader> inner_;
  std::shared_ptr<SkipLog> log_;
};

}  // namespace duskmap
