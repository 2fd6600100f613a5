// Shared by `duskmap run` and `duskmap report`: builds the report of a plan
// from one or more results folders, writes its tables and data, then draws
// the figures and report.md with scripts/plot_report.py.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "slam/experiment/experiment_config.h"
#include "slam/experiment/run_manifest.h"

namespace duskmap::cli {

struct ReportRequest {
  std::string config_path;
  std::vector<std::filesystem::path> results_dirs;
  std::filesystem::path output_dir;
  std::string paper_results;  // paper numbers JSON; empty = configs/paper_results.json when present
  bool figures = true;        // run scripts/plot_report.py
  bool allow_missing = false;  // a partial report: shards may be missing (their jobs are counted)
};

// Writes the report; prints where it went and the jobs still missing.
// Returns the number of missing jobs.
int WriteExperimentReport(const ReportRequest& request);

}  // namespace duskmap::cli
