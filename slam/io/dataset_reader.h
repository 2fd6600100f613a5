// The one interface every dataset reader implements (synthetic sessions, TUM
// RGB-D, RTAB-Map image releases and databases). A reader opens one dataset,
// which holds one or more sessions; frames are read per session in order.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "slam/core/rgbd_frame.h"

namespace duskmap {

class SessionReader {
 public:
  virtual ~SessionReader() = default;
  virtual const SessionInfo& info() const = 0;
  // The next frame, or nullopt at the end. Throws InputError naming the file
  // and the problem when a frame cannot be read.
  virtual std::optional<RgbdFrame> Next() = 0;
  // Restarts at the first frame.
  virtual void Rewind() = 0;
};

class DatasetReader {
 public:
  virtual ~DatasetReader() = default;
  virtual std::string format() const = 0;  // "synthetic", "tum", ...
  virtual std::vector<SessionInfo> Sessions() const = 0;
  // Opens the session with this name; throws InputError when there is none.
  virtual std::unique_ptr<SessionReader> OpenSession(const std::string& name) const = 0;
};

}  // namespace duskmap
