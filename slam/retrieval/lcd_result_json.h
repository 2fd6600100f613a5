// The loop closure detector's statuses' names (slam/core/json_codec.h), their
// one spelling, which LcdStatusName returns too.
#pragma once

#include <utility>

#include "slam/core/json_codec.h"
#include "slam/retrieval/lcd_result.h"

namespace duskmap {

template <>
struct JsonEnumNames<LcdStatus> {
  static constexpr std::pair<LcdStatus, const char*> kNames[] = {
      {LcdStatus::kAccepted, "accepted"},
      {LcdStatus::kBelowThreshold, "below_threshold"},
      {LcdStatus::kRejectedSinglePlace, "rejected_single_place"},
      {LcdStatus::kRejectedLoopRatio, "rejected_loop_ratio"},
      {LcdStatus::kBadSignature, "bad_signature"},
      {LcdStatus::kNoCandidates, "no_candidates"}};
};

}  // namespace duskmap
