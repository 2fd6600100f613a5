#include "experiments/report_output.h"

#include <algorithm>
#include <cstdlib>
#include <iostream>
#include <optional>

#include "slam/core/check.h"
#include "slam/core/json_fields.h"
#include "slam/experiment/shard_set.h"
#include "slam/io/folder_commit.h"
#include "slam/io/output_safety.h"
#include "slam/report/paper_reference.h"
#include "slam/report/report_builder.h"

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

// What a report folder holds: WriteReport's files, plot_report.py's
// report.md and figures/, and the partial files of a write cut short.
bool IsReportEntry(const std::string& name) {
  static const char* const kNames[] = {"tables",        "figures",      "tables.md",
                                       "tables.tex",    "cells.csv",    "timeline.csv",
                                       "consecutive.csv", "agreement.md", "agreement.json",
                                       "report.md"};
  for (const char* known : kNames) {
    const std::string partial = std::string(known) + ".partial-";
    if (name == known || name.rfind(partial, 0) == 0) return true;
  }
  return false;
}

// The first entry of `folder` a report does not write; empty when there is
// none (an empty folder, an earlier report, or one a killed run or a full
// disk left half-written: all of them the report's to replace).
std::string ForeignEntry(const fs::path& folder) {
  std::error_code error;
  for (fs::directory_iterator it(folder, error), end; !error && it != end; it.increment(error)) {
    const std::string name = it->path().filename().string();
    if (!IsReportEntry(name)) return name;
  }
  return error ? std::string("(unreadable: ") + error.message() + ")" : std::string();
}

bool IsReportFolder(const fs::path& path) {
  std::error_code error;
  return fs::is_directory(path, error) && ForeignEntry(path).empty();
}

OwnedOutput OwnedReportFolder() {
  return {"an earlier report (a folder of tables.md, cells.csv, tables/, figures/, ...)",
          &IsReportFolder};
}

// The report folder is new, empty, or an earlier report, complete or not;
// it is none of the inputs and does not hold the results.
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
  if (!fs::exists(fs::symlink_status(request.output_dir, error))) return;
  SLAM_THROW_IF_NOT(InputError, fs::is_directory(fs::symlink_status(request.output_dir, error)))
      << request.output_dir.string()
      << ": exists and is not an earlier report (not a folder); choose a new or empty --output";
  const std::string foreign = ForeignEntry(request.output_dir);
  SLAM_THROW_IF_NOT(InputError, foreign.empty())
      << request.output_dir.string() << ": exists and is not an earlier report (it holds "
      << foreign << ", which a report does not write); choose a new or empty --output";
}

}  // namespace

int WriteExperimentReport(const ReportRequest& request) {
  SLAM_THROW_IF_NOT(ConfigError, !request.results_dirs.empty()) << "report: no results folder";
  const ExperimentOptions options = ReadExperimentOptions(request.config_path);
  // The folders are the shards of one run, each once (and all of them unless
  // a partial report is asked for); the first one plans.
  const std::vector<ShardFolder> shards = ReadShardFolders(request.results_dirs);
  CheckShardsOfOneRun(shards);
  if (!request.allow_missing) CheckShardsComplete(shards);
  const RunManifest& manifest = shards.front().manifest;
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
  // Written whole into a staging folder beside it and published at the end:
  // a full disk or a killed run leaves the earlier report as it was (and at
  // most a staging folder, which the next report removes).
  StagedFolder staged(request.output_dir.string(), /*overwrite=*/true, OwnedReportFolder());
  const fs::path staging = staged.staging_path();
  try {
    WriteReport(report, staging);
  } catch (const InputError& e) {
    // (The message names a file of the staging folder, which is removed.)
    throw InputError(request.output_dir.string() + ": the report was not written, the earlier one "
                     "is as it was (" + e.what() + ")");
  }
  bool figures_drawn = false;
  if (request.figures) {
    const fs::path script = fs::path(DUSKMAP_SOURCE_DIR) / "scripts" / "plot_report.py";
    std::string command = "/usr/bin/python3 " + ShellQuote(script.string()) + " " +
                          ShellQuote(staging.string());
    for (const fs::path& dir : request.results_dirs) {
      command += " --jobs-dir " + ShellQuote((dir / "jobs").string());
    }
    command += " --title " + ShellQuote(fs::path(request.config_path).filename().string());
    command += " > /dev/null";
    figures_drawn = std::system(command.c_str()) == 0;
  }
  staged.Commit();
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
  if (request.figures && !figures_drawn) {
    std::cout << "note: figures not drawn (scripts/plot_report.py failed; see its error "
                 "above)\n";
  } else if (request.figures) {
    std::cout << "report: " << (request.output_dir / "report.md").string() << "\n";
  }
  return static_cast<int>(results.missing_jobs.size());
}

}  // namespace duskmap::cli
