#include "slam/experiment/session_clock.h"

#include <cstdio>

#include "slam/core/check.h"

namespace duskmap {

int ParseClockMinutes(const std::string& hh_mm) {
  int hours = -1;
  int minutes = -1;
  char tail = 0;
  const bool ok = std::sscanf(hh_mm.c_str(), "%d:%d%c", &hours, &minutes, &tail) == 2 &&
                  hours >= 0 && hours < 24 && minutes >= 0 && minutes < 60;
  SLAM_THROW_IF_NOT(ConfigError, ok) << "clock time '" << hh_mm << "': expected HH:MM";
  return hours * 60 + minutes;
}

}  // namespace duskmap
