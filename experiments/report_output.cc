#include "experiments/report_output.h"

#include <algorithm>
#include <cstdlib>
#include <iostream>
#include <optional>

#include "slam/core/check.h"
#include "slam/core/json_fields.h"
#include "slam/experiment/paper_reference.h"
#include "slam/experiment/report_builder.h"
#include "slam/io/output_safety.h"

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

// The report folder is new, empty, or an earlier report (tables.md and
// cells.csv); it is none of the inputs and does not hold the results.
void CheckReportFolder(const ReportRequest& request) {
  std::vector<NamedPath> inputs = {{"config", request.config_path}};
  for (const fs::path& dir : request.results_dirs) {
    inputs.push_back({"--results", (dir / "jobs").string()});
    inputs.push_back({"--results", (dir / "run.json").string()});
    SLAM_THROW_IF_NOT(InputError, !IsSameOrInside(dir, request.output_dir))
        << request.output_dir.string() << ": the report folder would hold the results folder "
        << dir.string() << "; choose another --output";
  }
  CheckOutputsApartFromInputs({{"--output", request.output_dir.string()}}, inputs);
  std::error_code error;
  if (!fs::exists(request.output_dir, error)) return;
  const bool report = fs::is_regular_file(request.output_dir / "tables.md", error) &&
                      fs::is_regular_file(request.output_dir / "cells.csv", error);
  SLAM_THROW_IF_NOT(InputError, fs::is_directory(request.output_dir, error) &&
                                    (report || fs::is_empty(request.output_dir, error)))
      << request.output_dir.string()
      << ": exists and is not an earlier report (no tables.md and cells.csv); choose a new or "
         "empty --output";
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
  // The config must be the one the run used (its record in run.json, when
  // the run wrote one): another config would label the results wrongly.
  if (!manifest.configuration.is_null()) {
    const std::string difference = FirstJsonDifference(manifest.configuration.value("experiment", nlohmann::json()),
                                                       ReadJsonFile(request.config_path));
    SLAM_THROW_IF_NOT(ConfigError, difference.empty())
        << request.config_path << ": not the config of the run in "
        << (request.results_dirs.front() / "run.json").string() << " (first difference at "
        << difference << ")";
  }
  for (const std::string& feature : manifest.features) {
    SLAM_THROW_IF_NOT(ConfigError, std::find(options.features.begin(), options.features.end(),
                                             feature) != options.features.end())
        << request.config_path << ": does not list feature " << feature << " of the run in "
        << (request.results_dirs.front() / "run.json").string();
  }
  CheckReportFolder(request);
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
  if (report.agreement) {
    const AgreementReport& agreement = *report.agreement;
    const TableDeviation* single = agreement.FindDeviation(kDeviationSingleMaps);
    const TableDeviation* multi = agreement.FindDeviation(kDeviationMultiMaps);
    const auto number = [](const std::optional<double>& value, int decimals) {
      return value ? FormatFixed(*value, decimals) : std::string("-");
    };
    std::cout << "agreement with the paper: single-session maps deviate by "
              << number(single->mean_abs_deviation, 1) << " points, multi-session maps by "
              << number(multi->mean_abs_deviation, 1) << " (held out), Spearman rho "
              << number(agreement.ranking.spearman_rho, 2);
    const RankAgreement& ranking = agreement.ranking;
    if (!ranking.close_pairs.empty() && ranking.spearman_rho_low && ranking.spearman_rho_high) {
      std::cout << " (" << FormatFixed(*ranking.spearman_rho_low, 2) << " to "
                << FormatFixed(*ranking.spearman_rho_high, 2) << " over the orders of features within "
                << FormatFixed(kRankResolutionPts, 1) << " points)";
    }
    std::cout << ", findings reproduced "
              << agreement.FindingsReproduced() << "/" << agreement.FindingsDecided() << " ("
              << (request.output_dir / "agreement.md").string() << ")\n";
  }
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
