// The report step shared by `duskmap run` and `duskmap report`: builds the
// report of a plan from one or more results folders, writes its tables and
// data, then draws the figures and report.md with scripts/plot_report.py.
// Prints nothing: what the CLI says comes back as an ExperimentReportOutcome.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "slam/experiment/run_manifest.h"
#include "slam/report/agreement.h"

namespace duskmap {

struct ExperimentReportRequest {
  std::string config_path;                          // the experiment config the runs used
  std::vector<std::filesystem::path> results_dirs;  // results folders of `duskmap run` (shards)
  std::filesystem::path output_dir;                 // the report folder
  // The paper's numbers (JSON); empty = default_paper_results when that file exists.
  std::string paper_results;
  std::filesystem::path default_paper_results;
  bool allow_missing = false;  // a partial report: shards may be missing (their jobs are counted)
  bool figures = true;         // run plot_script
  std::filesystem::path plot_script;  // scripts/plot_report.py (its stdout discarded)
};

struct ExperimentReportOutcome {
  std::vector<SkippedFeature> skipped_features;  // as the first results folder's run.json lists them
  std::vector<std::string> missing_jobs;         // jobs without results (their cells are empty)
  std::optional<AgreementReport> agreement;      // with the paper's numbers only
  bool figures_drawn = false;                    // plot_script ran and succeeded
};

// Writes the report, whole or not at all (a staging folder published at the
// end); ConfigError/InputError for a config that is not the runs', folders
// that are not the shards of one run (or not all of them, unless
// allow_missing), or an --output that is not a report folder.
ExperimentReportOutcome WriteExperimentReport(const ExperimentReportRequest& request);

}  // namespace duskmap
