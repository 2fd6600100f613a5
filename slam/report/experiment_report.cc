#include "slam/report/experiment_report.h"

#include <algorithm>
#include <cstdlib>

#include "slam/core/check.h"
#include "slam/core/json_fields.h"
#include "slam/experiment/experiment_config.h"
#include "slam/experiment/shard_set.h"
#include "slam/io/folder_commit.h"
#include "slam/io/output_safety.h"
#include "slam/report/paper_reference.h"
#include "slam/report/report_builder.h"

namespace duskmap {
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
                                       "consecutive.csv", "scaling.csv", "agreement.md",
                                       "agreement.json", "report.md"};
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
void CheckReportFolder(const ExperimentReportRequest& request) {
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

// The config must be the one the run used (its record in run.json, when
// the run wrote one): another config would label the results wrongly.
void CheckConfigIsTheRuns(const ExperimentReportRequest& request, const ExperimentOptions& options,
                          const RunManifest& manifest) {
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
}

std::optional<PaperReference> LoadPaper(const ExperimentReportRequest& request) {
  std::string paper_file = request.paper_results;
  if (paper_file.empty() && !request.default_paper_results.empty() &&
      fs::exists(request.default_paper_results)) {
    paper_file = request.default_paper_results.string();
  }
  if (paper_file.empty()) return std::nullopt;
  return PaperReference::Load(paper_file);
}

// scripts/plot_report.py over the staged report (its stdout discarded, its
// errors on stderr); true when it succeeded.
bool DrawFigures(const ExperimentReportRequest& request, const fs::path& staging) {
  std::string command = "/usr/bin/python3 " + ShellQuote(request.plot_script.string()) + " " +
                        ShellQuote(staging.string());
  for (const fs::path& dir : request.results_dirs) {
    command += " --jobs-dir " + ShellQuote((dir / "jobs").string());
  }
  command += " --title " + ShellQuote(fs::path(request.config_path).filename().string());
  command += " > /dev/null";
  return std::system(command.c_str()) == 0;
}

}  // namespace

ExperimentReportOutcome WriteExperimentReport(const ExperimentReportRequest& request) {
  SLAM_THROW_IF_NOT(ConfigError, !request.results_dirs.empty()) << "report: no results folder";
  const ExperimentOptions options = ReadExperimentOptions(request.config_path);
  // The folders are the shards of one run, each once (and all of them unless
  // a partial report is asked for); the first one plans.
  const std::vector<ShardFolder> shards = ReadShardFolders(request.results_dirs);
  CheckShardsOfOneRun(shards);
  if (!request.allow_missing) CheckShardsComplete(shards);
  const RunManifest& manifest = shards.front().manifest;
  CheckConfigIsTheRuns(request, options, manifest);
  CheckReportFolder(request);
  const ExperimentPlan plan = PlanFromManifest(options, manifest);
  ExperimentOptions reported = options;
  reported.features = manifest.features;
  const ExperimentResults results = CollectResults(plan, request.results_dirs);
  const std::optional<PaperReference> paper = LoadPaper(request);

  ExperimentReport report = BuildReport(reported, plan, results, paper);
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
  ExperimentReportOutcome outcome;
  if (request.figures) outcome.figures_drawn = DrawFigures(request, staging);
  staged.Commit();
  outcome.skipped_features = manifest.skipped_features;
  outcome.missing_jobs = results.missing_jobs;
  outcome.agreement = std::move(report.agreement);
  return outcome;
}

}  // namespace duskmap
