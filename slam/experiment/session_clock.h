// The clock time of a dataset's sessions, which closest-in-time maps and
// consecutive pairs are planned by (job_plan.h) and which an experiment
// config may give for sessions whose dataset has none (experiment_config.h).
#pragma once

#include <map>
#include <string>

namespace duskmap {

// Clock time of each session, in minutes since midnight.
using SessionClock = std::map<std::string, int>;

// Parses "HH:MM" into minutes since midnight; throws ConfigError otherwise.
int ParseClockMinutes(const std::string& hh_mm);

}  // namespace duskmap
