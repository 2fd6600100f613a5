// The paper's map notation, parsed into what a map job must build:
//   "3"            single-session map from mapping session 3
//   "1+3+5"        sessions replayed back to back into one map, no reduction
//   "1-2-3-4-5-6"  the same with graph reduction
//   "1|2|3|4|5|6"  no map of its own: each localization session uses the single
//                  map among these whose clock time is closest to its own
// Session names may be any non-empty string without '+', '-' or '|'.
#pragma once

#include <string>
#include <vector>

namespace duskmap {

enum class MapKind {
  kSingle,         // "3"
  kMerged,         // "1+3+5"
  kReduced,        // "1-2-3-4-5-6"
  kClosestInTime,  // "1|2|3|4|5|6"
};

const char* MapKindName(MapKind kind);

struct MapSpec {
  std::string label;                  // as written, e.g. "1+3+5"
  MapKind kind = MapKind::kSingle;
  std::vector<std::string> sessions;  // in replay order

  bool BuildsItsOwnMap() const { return kind != MapKind::kClosestInTime; }
};

// Throws ConfigError naming the label and the problem (empty session name,
// mixed separators, a session listed twice).
MapSpec ParseMapSpec(const std::string& label);

}  // namespace duskmap
