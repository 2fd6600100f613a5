// `duskmap run`: runs an experiment matrix (feature extraction per session,
// map building, localization of every session on every map, consecutive
// sessions) with cached features, parallel jobs, resume and shards, then
// writes the report (unsharded runs; shards are merged by `duskmap report`).
// The run is the library's (slam/experiment/run_setup.h, the report's
// slam/report/experiment_report.h); this file parses the flags and prints.
#include <cmath>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>

#include "experiments/command_registry.h"
#include "experiments/report_summary.h"
#include "slam/core/check.h"
#include "slam/experiment/run_setup.h"

namespace duskmap::cli {
namespace {

struct RunArgs {
  RunSetupOptions setup;  // the flags the library's run takes, bound directly
  bool report = true;
  bool figures = true;
};

std::string FormatDuration(double seconds) {
  const long s = std::lround(std::max(0.0, seconds));
  std::ostringstream out;
  out << s / 3600 << ":" << std::setw(2) << std::setfill('0') << (s / 60) % 60 << ":"
      << std::setw(2) << std::setfill('0') << s % 60;
  return out.str();
}

void PrintSkippedFeatures(const std::vector<SkippedFeature>& skipped_features) {
  for (const SkippedFeature& skipped : skipped_features) {
    std::cout << "note: feature " << skipped.label << " skipped: " << skipped.reason << "\n";
  }
}

// (Said once the run is accepted: a refusal stays one line.)
void PrintRunStart(const PreparedRun& run, const std::string& shard) {
  std::cout << "dataset: " << run.dataset_files << " files, " << std::fixed
            << std::setprecision(2) << run.dataset_bytes / 1e9 << " GB checksummed in "
            << std::setprecision(1) << run.checksum_s << " s\n"
            << std::defaultfloat;
  std::cout << "duskmap run: " << run.plan.jobs.size() << " jobs (" << run.total_frames
            << " frame passes), " << run.parallel_jobs << " at once, results in "
            << run.output_dir.string()
            << (run.shard.count > 1 ? ", shard " + shard : std::string()) << "\n"
            << std::flush;
}

// One line per finished job; on a terminal, one line rewritten in place.
void PrintProgress(const RunProgress& progress, bool terminal) {
  const JobRunProgress& p = progress.jobs;
  std::ostringstream line;
  line << "[" << p.finished << "/" << p.total << " jobs" << (p.failed ? ", " : "")
       << (p.failed ? std::to_string(p.failed) + " failed" : "") << "] " << std::fixed
       << std::setprecision(1) << progress.frames_per_s << " frames/s, elapsed "
       << FormatDuration(p.elapsed_s) << ", ETA " << FormatDuration(progress.eta_s) << "  "
       << p.last_job_id;
  if (terminal) {
    std::cout << "\r\033[K" << line.str() << std::flush;
  } else {
    std::cout << line.str() << "\n" << std::flush;
  }
}

// The failures last: when the disk is full, writing timing.json throws
// next, and the jobs' own reasons must not be lost behind it.
void PrintRunSummary(const JobRunSummary& summary) {
  std::cout << "done in " << FormatDuration(summary.wall_s) << ": " << summary.executed
            << " jobs run, " << summary.resumed << " resumed, " << summary.failures.size()
            << " failed; job time by kind:";
  for (const auto& [kind, seconds] : summary.busy_s_by_kind) {
    std::cout << " " << JobKindName(kind) << " " << std::fixed << std::setprecision(1)
              << seconds << " s";
  }
  std::cout << "\n";
  for (const JobFailure& failure : summary.failures) {
    std::cout << "failed: " << failure.job_id << ": " << failure.message << "\n";
  }
  std::cout.flush();
}

int RunExperiment(const RunArgs& args) {
  PreparedRun run = PrepareRun(args.setup, &PrintSkippedFeatures);
  PrintRunStart(run, args.setup.shard);
  const bool terminal = StdoutIsTerminal();
  const JobRunSummary summary = RunPreparedJobs(
      run, [terminal](const RunProgress& progress) { PrintProgress(progress, terminal); });
  if (terminal) std::cout << "\n";
  PrintRunSummary(summary);
  WriteRunTiming(summary, run.output_dir / "timing.json");
  if (args.report && run.shard.count == 1) {
    const ExperimentReportRequest request =
        ReportRequestFor(args.setup.config_path, {run.output_dir}, run.output_dir / "report", args.figures);
    PrintReportOutcome(request, WriteExperimentReport(request));
  }
  SLAM_THROW_IF_NOT(Error, summary.ok())
      << summary.failures.size() << " of " << run.plan.jobs.size() << " jobs failed (see above)";
  return 0;
}

RunFn SetupRun(CLI::App& command) {
  auto args = std::make_shared<RunArgs>();
  RunSetupOptions& setup = args->setup;
  setup.program_version = DUSKMAP_VERSION;
  command.add_option("config", setup.config_path, "experiment config (configs/*.json)")->required();
  command.add_option("--output", setup.output_dir,
                     "results folder (default: out/<config name without .json>)");
  command.add_option("--jobs", setup.parallel_jobs, "jobs run at once (default: one per CPU)");
  command.add_flag("--resume", setup.resume, "continue an interrupted run, keeping finished jobs");
  command.add_flag("--overwrite", setup.overwrite, "redo every job of an earlier run");
  command.add_option("--shard", setup.shard,
                     "run shard i of n (i/n, 0-based); merge shards with `duskmap report`");
  command.add_flag("--allow-unordered", setup.allow_unordered,
                   "read rgb.txt/depth.txt as recorded: sort them and drop unmatched frames (real TUM recordings)");
  command.add_flag("!--no-report", args->report, "do not write the report after the run");
  command.add_flag("!--no-figures", args->figures, "write the report's tables only");
  command.add_option("--feature-cache", setup.feature_cache,
                     "folder of extracted features kept across runs: an extract job whose "
                     "session's files (by content), program, feature options, model or h5 "
                     "file and frame selection match an entry "
                     "restores it instead of extracting (docs/experiments.md)");
  return [args] { return RunExperiment(*args); };
}

const bool kRegistered = RegisterCommand(
    {"run", "Run an experiment matrix (features x maps x sessions) and write its report",
     &SetupRun});

}  // namespace
}  // namespace duskmap::cli
