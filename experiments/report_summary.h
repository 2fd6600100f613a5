// Shared by `duskmap run` and `duskmap report`: the report request with the
// program's own paper numbers and figure script, and what is printed once
// the report is written.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "slam/report/experiment_report.h"

namespace duskmap::cli {

// configs/paper_results.json (when --paper is not given) and
// scripts/plot_report.py of the program's source tree.
ExperimentReportRequest ReportRequestFor(const std::string& config_path,
                                         std::vector<std::filesystem::path> results_dirs,
                                         const std::filesystem::path& output_dir, bool figures);

// Prints the skipped features, the jobs still missing, where the tables,
// the agreement and report.md went (or that the figures were not drawn).
void PrintReportOutcome(const ExperimentReportRequest& request,
                        const ExperimentReportOutcome& outcome);

}  // namespace duskmap::cli
