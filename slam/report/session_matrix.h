// Re-localization of each single-session map on each localization session,
// per feature: the matrix the paper draws as a figure, and what its finding
// "best on the diagonal, worst day-to-night and night-to-day" is decided on.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace duskmap {

struct SingleMapMatrix {
  std::vector<std::string> map_rows;  // the single-session map rows, as configured
  std::vector<std::string> sessions;  // the localization sessions, as configured
  // Per session: the map row closest to it in time (what the closest-in-time
  // row used), or "" when the experiment has no closest-in-time row.
  std::vector<std::string> closest_row;
  // Re-localized frames (%), pct[feature][row index][session index];
  // nullopt where the job did not run.
  std::map<std::string, std::vector<std::vector<std::optional<double>>>> pct;
};

}  // namespace duskmap
