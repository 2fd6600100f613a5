#include "slam/datasets/skipping_session_reader.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "slam/core/check.h"

namespace duskmap {
namespace {

// Frames 0..4; frames listed in `bad` throw after being consumed. With
// `stuck`, a failing frame is never consumed (a reader breaking the contract).
class ScriptedSession : public SessionReader {
 public:
  ScriptedSession(std::vector<int> bad, bool stuck) : bad_(std::move(bad)), stuck_(stuck) {
    info_.name = "s";
    info_.num_frames = 5;
  }
  const SessionInfo& info() const override { return info_; }
  void Rewind() override { next_ = 0; }
  std::optional<RgbdFrame> Next() override {
    if (next_ >= 5) return std::nullopt;
    const int index = stuck_ ? next_ : next_++;
    if (std::find(bad_.begin(), bad_.end(), index) != bad_.end()) {
      throw InputError("s: frame " + std::to_string(index) + " is bad");
    }
    if (stuck_) ++next_;
    RgbdFrame frame;
    frame.frame_index = index;
    return frame;
  }

 private:
  SessionInfo info_;
  std::vector<int> bad_;
  bool stuck_;
  int next_ = 0;
};

TEST(SkippingSessionReader, SkipsAndLogsBadFrames) {
  auto log = std::make_shared<SkipLog>();
  SkippingSessionReader reader(std::make_unique<ScriptedSession>(std::vector<int>{1, 2, 4}, false),
                               log);
  std::vector<int64_t> read;
  while (auto frame = reader.Next()) read.push_back(frame->frame_index);
  EXPECT_EQ(read, (std::vector<int64_t>{0, 3}));
  EXPECT_EQ(log->count(), 3);
  EXPECT_EQ(log->messages()[2], "s: frame 4 is bad");
}

TEST(SkippingSessionReader, RethrowsWhenTheReaderMakesNoProgress) {
  auto log = std::make_shared<SkipLog>();
  SkippingSessionReader reader(std::make_unique<ScriptedSession>(std::vector<int>{0}, true), log);
  EXPECT_THROW(reader.Next(), InputError);
}

TEST(DatasetReadOptions, SkippingNeedsALog) {
  DatasetReadOptions options;
  options.skip_bad_frames = true;
  EXPECT_THROW(options.Check(), ConfigError);
  options.skip_log = std::make_shared<SkipLog>();
  EXPECT_NO_THROW(options.Check());
  EXPECT_THROW(ReportBadFrame(DatasetReadOptions(), "x"), InputError);
  ReportBadFrame(options, "x");
  EXPECT_EQ(options.skip_log->count(), 1);
}

}  // namespace
}  // namespace duskmap
