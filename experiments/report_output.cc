#include "experiments/report_output.h"

#include <cstdlib>
#include <iostream>
#include <optional>

#include "slam/core/check.h"
#include "slam/experiment/paper_reference.h"
#include "slam/experiment/report_builder.h"

namespace duskmap::cli {
namespace fs = std::filesystem;
namespace {

std::string ShellQuote(const std::string& text) {
  std::string quoted = "'";
  for (char c : text) {
    if (c == '\'') {
      quoted += "'\\''";
    } else {
      quoted += c;
    }
  }
  return quoted + "'";
}

}  // namespace

int WriteExperimentReport(const ReportRequest& request) {
  SLAM_THROW_IF_NOT(ConfigError, !request.results_dirs.empty()) << "report: no results folder";
  const ExperimentOptions options = ReadExperimentOptions(request.config_path);
  // Every shard records the same features and clock; the first one plans.
  const RunManifest manifest = ReadRunManifest(request.results_dirs.front());
  for (size_t i = 1; i < request.results_dirs.size(); ++i) {
    const RunManifest other = ReadRunManifest(request.results_dirs[i]);
    SLAM_THROW_IF_NOT(InputError, other.features == manifest.features &&
                                      other.session_clock == manifest.session_clock)
        << (request.results_dirs[i] / "run.json").string()
        << ": another run (features or sessions differ from "
        << (request.results_dirs.front() / "run.json").string() << ")";
  }
  const ExperimentPlan plan = PlanFromManifest(options, manifest);
  ExperimentOptions reported = options;
  reported.features = manifest.features;
  const ExperimentResults results = CollectResults(plan, request.results_dirs);

  std::optional<PaperReference> paper;
  std::string paper_file = request.paper_results;
  if (paper_file.empty()) {
    const fs::path fallback = fs::path(DUSKMAP_SOURCE_DIR) / "configs" / "paper_results.json";
    if (fs::exists(fallback)) paper_file = fallback.string();
  }
  if (!paper_file.empty()) paper = PaperReference::Load(paper_file);

  const ExperimentReport report = BuildReport(reported, plan, results, paper);
  WriteReport(report, request.output_dir);
  for (const SkippedFeature& skipped : manifest.skipped_features) {
    std::cout << "note: feature " << skipped.label << " skipped: " << skipped.reason << "\n";
  }
  if (!results.missing_jobs.empty()) {
    std::cout << "note: " << results.missing_jobs.size()
              << " jobs have no results yet (their cells are empty), e.g. "
              << results.missing_jobs.front() << "\n";
  }
  std::cout << "tables: " << (request.output_dir / "tables.md").string() << "\n";
  if (request.figures) {
    const fs::path script = fs::path(DUSKMAP_SOURCE_DIR) / "scripts" / "plot_report.py";
    std::string command = "/usr/bin/python3 " + ShellQuote(script.string()) + " " +
                          ShellQuote(request.output_dir.string());
    for (const fs::path& dir : request.results_dirs) {
      command += " --jobs-dir " + ShellQuote((dir / "jobs").string());
    }
    command += " --title " + ShellQuote(fs::path(request.config_path).filename().string());
    command += " > /dev/null";
    if (std::system(command.c_str()) != 0) {
      std::cout << "note: figures not drawn (scripts/plot_report.py failed; see its error "
                   "above)\n";
    } else {
      std::cout << "report: " << (request.output_dir / "report.md").string() << "\n";
    }
  }
  return static_cast<int>(results.missing_jobs.size());
}

}  // namespace duskmap::cli
