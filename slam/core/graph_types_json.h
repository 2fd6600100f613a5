// The link types' names (slam/core/json_codec.h), their one spelling, which
// LinkTypeName returns too: "odometry", "loop_closure", "proximity", "merged", "prior".
#pragma once

#include <utility>

#include "slam/core/graph_types.h"
#include "slam/core/json_codec.h"

namespace duskmap {

template <>
struct JsonEnumNames<LinkType> {
  static constexpr std::pair<LinkType, const char*> kNames[] = {
      {LinkType::kOdometry, "odometry"},
      {LinkType::kLoopClosure, "loop_closure"},
      {LinkType::kProximity, "proximity"},
      {LinkType::kMerged, "merged"},
      {LinkType::kPrior, "prior"}};
};

}  // namespace duskmap
