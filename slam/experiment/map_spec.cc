#include "slam/experiment/map_spec.h"

#include <set>

#include "slam/core/check.h"

namespace duskmap {
namespace {

std::vector<std::string> Split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::string current;
  for (char c : text) {
    if (c == separator) {
      parts.push_back(current);
      current.clear();
    } else {
      current.push_back(c);
    }
  }
  parts.push_back(current);
  return parts;
}

}  // namespace

const char* MapKindName(MapKind kind) {
  switch (kind) {
    case MapKind::kSingle: return "single";
    case MapKind::kMerged: return "merged";
    case MapKind::kReduced: return "reduced";
    case MapKind::kClosestInTime: return "closest_in_time";
  }
  return "unknown";
}

MapSpec ParseMapSpec(const std::string& label) {
  SLAM_THROW_IF_NOT(ConfigError, !label.empty()) << "map '': empty map label";
  const std::string separators = "+-|";
  char separator = 0;
  for (char c : label) {
    if (separators.find(c) == std::string::npos) continue;
    SLAM_THROW_IF_NOT(ConfigError, separator == 0 || separator == c)
        << "map '" << label << "': mixes separators '" << separator << "' and '" << c << "'";
    separator = c;
  }
  MapSpec spec;
  spec.label = label;
  switch (separator) {
    case 0: spec.kind = MapKind::kSingle; break;
    case '+': spec.kind = MapKind::kMerged; break;
    case '-': spec.kind = MapKind::kReduced; break;
    default: spec.kind = MapKind::kClosestInTime; break;
  }
  spec.sessions = separator == 0 ? std::vector<std::string>{label} : Split(label, separator);
  std::set<std::string> seen;
  for (const std::string& session : spec.sessions) {
    SLAM_THROW_IF_NOT(ConfigError, !session.empty())
        << "map '" << label << "': empty session name";
    SLAM_THROW_IF_NOT(ConfigError, seen.insert(session).second)
        << "map '" << label << "': session '" << session << "' listed twice";
  }
  return spec;
}

}  // namespace duskmap
