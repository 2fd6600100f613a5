// Turns the job summaries of a finished (or merged, sharded) run into the
// paper's tables, each cell beside the paper's value, plus the per-cell data
// the figures are drawn from.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "slam/experiment/experiment_config.h"
#include "slam/experiment/job_plan.h"
#include "slam/experiment/job_results.h"
#include "slam/report/agreement.h"
#include "slam/report/paper_reference.h"
#include "slam/report/report_table.h"
#include "slam/report/session_matrix.h"

namespace duskmap {

// Summaries found for a plan; a job without a summary (not run yet, failed,
// or in another shard's folder not merged) leaves its cells empty.
struct ExperimentResults {
  std::map<std::string, LocalizationJobSummary> localization;  // by job id
  std::map<std::string, MapJobSummary> maps;                   // by job id
  std::vector<std::string> missing_jobs;
};

// Reads the summaries of `plan`'s jobs from one or more results folders (the
// first folder holding a job wins). Throws InputError for a malformed summary.
ExperimentResults CollectResults(const ExperimentPlan& plan,
                                 const std::vector<std::filesystem::path>& results_dirs);

struct ExperimentReport {
  std::vector<ReportTable> tables;
  // One line per matrix cell: feature,row,session,relocalized_pct,... for figures.
  std::string cells_csv;
  // One line per frame of each localization job, for the over-time figure.
  std::string timeline_csv;
  std::string consecutive_csv;
  // The scaling curve's data (scaling_tables.h); empty without a config's "scaling".
  std::string scaling_csv;
  SingleMapMatrix single_maps;
  // How far the tables agree with the paper; only with the paper's numbers.
  std::optional<AgreementReport> agreement;
};

ExperimentReport BuildReport(const ExperimentOptions& options, const ExperimentPlan& plan,
                             const ExperimentResults& results,
                             const std::optional<PaperReference>& paper);

// Writes tables.md, tables.tex, one CSV per table, the figure data and, with
// the paper's numbers, agreement.md and agreement.json into `dir` (created
// when absent); scripts/plot_report.py puts them together in report.md.
void WriteReport(const ExperimentReport& report, const std::filesystem::path& dir);

}  // namespace duskmap
