// The scaling curve of the report (issue 46): for each map the experiment
// config lists under "scaling" (ExperimentOptions::scaling), in its order,
// what the report's other tables and the localization jobs on that map
// measured, against the number of sessions in the map: nodes, median LCD + TE
// per frame, memory needed for localization, map open time and
// re-localization. One table per measure (rows the curve's maps, columns the
// features) and scaling.csv, the data of figures/scaling.png.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "slam/experiment/experiment_config.h"
#include "slam/experiment/job_plan.h"
#include "slam/experiment/job_results.h"
#include "slam/report/report_table.h"

namespace duskmap {

// One map of the curve for one feature; a measure is empty when no job
// measured it (a job not run, or in a shard not merged).
struct ScalingPoint {
  std::string feature;
  std::string map;   // the map's label, as in the config
  int sessions = 0;  // sessions replayed into the map
  // The report's own tables' cells for this map (same definitions).
  std::optional<double> nodes;            // graph size after reduction
  std::optional<double> memory_mb;        // memory needed for localization
  std::optional<double> relocalized_pct;  // cumulative over the localization sessions
  std::optional<double> correct_pct;      // within 0.5 m/5°, likewise
  // Means over the localization jobs on the map (its matrix cells).
  std::optional<double> lcd_te_ms;  // each job's median LCD + TE per frame
  std::optional<double> lcd_ms;     // mean loop closure detection per frame
  std::optional<double> te_ms;      // mean transformation estimation per frame
  // As the timing budget table defines them: a load over the jobs that
  // loaded the map (not map_from_cache), the setup over every job.
  std::optional<double> map_load_s;
  std::optional<double> localizer_setup_s;
  std::optional<double> map_open_s;  // map_load_s + localizer_setup_s
};

struct ScalingSection {
  std::vector<ScalingPoint> points;  // feature by feature, each in the curve's order
  std::vector<ReportTable> tables;
  std::string csv;  // scaling.csv: feature,map,sessions,<measures>
};

using LocalizationSummaries = std::map<std::string, LocalizationJobSummary>;  // by job id

// The tables' row labels, one per curve map: "<sessions> (<label>)", a label
// longer than 24 characters shortened to its first and last sessions
// ("48 (a1-...-h6)") unless two rows would then read the same.
std::vector<std::string> ScalingRowLabels(const std::vector<MapSpec>& curve);

// Empty (no tables, no csv) when the config has no scaling curve.
// `tables` are the report's tables built so far (the graph size, memory and
// re-localization tables are read by id, report_table_ids.h); `localization`
// the localization jobs' summaries by job id.
ScalingSection BuildScalingSection(const ExperimentOptions& options, const ExperimentPlan& plan,
                                   const LocalizationSummaries& localization,
                                   const std::vector<ReportTable>& tables);

}  // namespace duskmap
