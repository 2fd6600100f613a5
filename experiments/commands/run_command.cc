// `duskmap run`: runs an experiment matrix (feature extraction per session,
// map building, localization of every session on every map, consecutive
// sessions) with cached features, parallel jobs, resume and shards, then
// writes the report (unsharded runs; shards are merged by `duskmap report`).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <fstream>
#include <iostream>
#include <iterator>
#include <map>
#include <memory>
#include <sstream>
#include <thread>

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

#include "experiments/command_registry.h"
#include "experiments/report_summary.h"
#include "slam/core/check.h"
#include "slam/core/checksum.h"
#include "slam/core/json_fields.h"
#include "slam/core/timer.h"
#include "slam/datasets/dataset_factory.h"
#include "slam/datasets/dataset_identity.h"
#include "slam/engine/engine_options.h"
#include "slam/experiment/engine_executor.h"
#include "slam/experiment/feature_files.h"
#include "slam/experiment/job_runner.h"
#include "slam/experiment/run_manifest.h"
#include "slam/io/folder_commit.h"
#include "slam/io/output_safety.h"

namespace duskmap::cli {
namespace fs = std::filesystem;
namespace {

struct RunArgs {
  std::string config;
  std::string output;
  int jobs = 0;  // 0 = one per hardware thread
  bool resume = false;
  bool overwrite = false;
  std::string shard = "0/1";
  bool report = true;
  bool figures = true;
  bool allow_unordered = false;
  std::string feature_cache;  // folder of feature caches shared across runs; empty = none
};

std::pair<int, int> ParseShard(const std::string& text) {
  int index = -1;
  int count = -1;
  char slash = 0;
  std::istringstream in(text);
  in >> index >> slash >> count;
  SLAM_THROW_IF_NOT(ConfigError, in && in.peek() == EOF && slash == '/' && count >= 1 &&
                                     index >= 0 && index < count)
      << "--shard " << text << ": expected i/n with 0 <= i < n";
  return {index, count};
}

std::string FormatDuration(double seconds) {
  const long s = std::lround(std::max(0.0, seconds));
  std::ostringstream out;
  out << s / 3600 << ":" << std::setw(2) << std::setfill('0') << (s / 60) % 60 << ":"
      << std::setw(2) << std::setfill('0') << s % 60;
  return out.str();
}

// Frames each job processes, for the frames/s and ETA of the progress line.
std::map<std::string, int64_t> FramesPerJob(const ExperimentPlan& plan,
                                            const ExperimentOptions& options,
                                            const std::vector<SessionInfo>& sessions) {
  std::map<std::string, int64_t> session_frames;
  for (const SessionInfo& s : sessions) {
    int64_t n = (s.num_frames + options.frame_step - 1) / options.frame_step;
    if (options.max_frames_per_session > 0) n = std::min<int64_t>(n, options.max_frames_per_session);
    session_frames[s.name] = n;
  }
  std::map<std::string, int64_t> frames;
  for (const Job& job : plan.jobs) {
    int64_t n = 0;
    if (job.kind == JobKind::kBuildMap) {
      for (const std::string& s : job.map.sessions) n += session_frames[s];
    } else {
      n = session_frames[job.session];
    }
    frames[job.id] = n;
  }
  return frames;
}

// A results folder is new, empty, or one `duskmap run` wrote (run.json):
// a run never writes its jobs/ and report/ into a folder of other files.
void CheckOutputFolder(const fs::path& output, const RunArgs& args, const RunManifest& manifest) {
  std::error_code error;
  if (!fs::exists(output, error)) return;
  SLAM_THROW_IF_NOT(InputError, fs::is_directory(output, error))
      << output.string() << ": exists and is not a folder; choose another --output";
  if (!fs::exists(output / "run.json", error)) {
    // (A run killed before it wrote run.json leaves only its lock file.)
    bool empty = true;
    for (const fs::directory_entry& entry : fs::directory_iterator(output, error)) {
      if (entry.path().filename() != FolderLock::kFileName) empty = false;
    }
    SLAM_THROW_IF_NOT(InputError, empty && !error)
        << output.string()
        << ": not a duskmap results folder (no run.json) and not empty; choose a new or empty "
           "--output";
    return;
  }
  SLAM_THROW_IF_NOT(ConfigError, args.resume || args.overwrite)
      << output.string()
      << ": holds an earlier run; pass --resume to continue it or --overwrite to redo every job";
  if (!args.resume) return;
  CheckResumable(ReadRunManifest(output), manifest, output);
}

// Wall-clock times of this invocation (not deterministic, kept out of the
// report's tables): total, summed job time per kind, each job's time.
void WriteRunTiming(const JobRunSummary& summary, const fs::path& path) {
  nlohmann::json json;
  json["wall_s"] = summary.wall_s;
  json["executed"] = summary.executed;
  json["resumed"] = summary.resumed;
  for (const auto& [kind, seconds] : summary.busy_s_by_kind) json["job_s_by_kind"][JobKindName(kind)] = seconds;
  json["job_s"] = summary.job_wall_s;
  WriteFileAtomically(path.string(), [&](std::ostream& out) { out << json.dump(1) << "\n"; });
}

// A checksum of the running executable: features a rebuilt program extracts
// are never taken for this one's.
std::string ProgramChecksum() {
  std::ifstream in("/proc/self/exe", std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  SLAM_THROW_IF_NOT(InputError, in.good() || in.eof())
      << "/proc/self/exe: cannot read the program to key the feature cache";
  return Checksum64Hex(bytes.data(), bytes.size());
}

// The dataset's identity and how it was read (both shape the results).
nlohmann::json DatasetIdentityRead(const ExperimentOptions& options,
                                   const std::vector<SessionInfo>& sessions, bool allow_unordered) {
  nlohmann::json identity = DatasetIdentity(options.dataset_path, options.dataset_format, sessions);
  identity["allow_unordered"] = allow_unordered;
  return identity;
}

RunFn SetupRun(CLI::App& command) {
  auto args = std::make_shared<RunArgs>();
  command.add_option("config", args->config, "experiment config (configs/*.json)")->required();
  command.add_option("--output", args->output,
                     "results folder (default: out/<config name without .json>)");
  command.add_option("--jobs", args->jobs, "jobs run at once (default: one per CPU)");
  command.add_flag("--resume", args->resume, "continue an interrupted run, keeping finished jobs");
  command.add_flag("--overwrite", args->overwrite, "redo every job of an earlier run");
  command.add_option("--shard", args->shard,
                     "run shard i of n (i/n, 0-based); merge shards with `duskmap report`");
  command.add_flag("--allow-unordered", args->allow_unordered,
                   "read rgb.txt/depth.txt as recorded: sort them and drop unmatched frames (real TUM recordings)");
  command.add_flag("!--no-report", args->report, "do not write the report after the run");
  command.add_flag("!--no-figures", args->figures, "write the report's tables only");
  command.add_option("--feature-cache", args->feature_cache,
                     "folder of extracted features kept across runs: an extract job whose "
                     "session's files (by content), program, feature options, model or h5 "
                     "file and frame selection match an entry "
                     "restores it instead of extracting (docs/experiments.md)");
  return [args] {
    const ExperimentOptions options = ReadExperimentOptions(args->config);
    const EngineOptions engine = options.engine_config.empty()
                                     ? EngineOptions()
                                     : ReadEngineOptionsFile(options.engine_config);
    const auto [shard_index, shard_count] = ParseShard(args->shard);
    const fs::path output =
        args->output.empty() ? fs::path("out") / fs::path(args->config).stem() : fs::path(args->output);
    SLAM_THROW_IF_NOT(ConfigError, args->jobs >= 0 && args->jobs <= 4096)
        << "--jobs: must be in [0, 4096], got " << args->jobs;
    const int jobs = args->jobs > 0 ? args->jobs
                                    : std::max(1u, std::thread::hardware_concurrency());

    SLAM_THROW_IF_NOT(ConfigError, !(args->resume && args->overwrite))
        << "--resume and --overwrite: give one (continue the earlier run, or redo it)";
    CheckOutputsApartFromInputs({{"--output", output.string()}, {"--feature-cache", args->feature_cache}},
                                {{"config", args->config},
                                 {"engine_config", options.engine_config},
                                 {"dataset.path", options.dataset_path}});
    SLAM_THROW_IF_NOT(ConfigError, args->feature_cache.empty() ||
                                       !IsSameOrInside(args->feature_cache, output))
        << "--feature-cache " << args->feature_cache << ": must lie outside --output "
        << output.string() << " (an --overwrite of the results would remove it)";
    DatasetReadOptions read;
    read.allow_unordered = args->allow_unordered;
    const auto dataset = OpenDataset(options.dataset_path, options.dataset_format, read);
    const std::vector<SessionInfo> sessions = dataset->Sessions();
    std::vector<std::string> session_names;
    for (const SessionInfo& s : sessions) session_names.push_back(s.name);
    // A session the dataset lacks fails here, before any job runs.
    CheckSessionsExist(options, session_names, args->config);
    CheckDeclaredFeatureFiles(options);
    RunManifest manifest;
    manifest.config_path = args->config;
    manifest.dataset_path = options.dataset_path;
    manifest.session_clock = SessionClockOf(sessions, options.session_clock_times);
    manifest.shard_index = shard_index;
    manifest.shard_count = shard_count;
    SelectRunnableFeatures(options,
                           {engine.features.superpoint.model_path, engine.matcher.superglue.model_path},
                           &manifest);
    for (const SkippedFeature& skipped : manifest.skipped_features) {
      std::cout << "note: feature " << skipped.label << " skipped: " << skipped.reason << "\n";
    }
    SLAM_THROW_IF_NOT(ConfigError, !manifest.features.empty())
        << args->config << ": every feature type was skipped";
    const ExperimentPlan full_plan = PlanFromManifest(options, manifest);
    const ExperimentPlan plan = SelectShard(full_plan, shard_index, shard_count);
    // Every file of the dataset and every model or h5 file is read once here:
    // content, not size or time, decides what a resume or the feature cache reuses.
    Stopwatch checksum_watch;
    const nlohmann::json dataset_identity =
        DatasetIdentityRead(options, sessions, args->allow_unordered);
    const nlohmann::json feature_files = RunFeatureFileChecksums(options, engine, manifest.features);
    const double checksum_s = checksum_watch.ElapsedMs() / 1e3;
    SetRunConfiguration(ReadJsonFile(args->config),
                        options.engine_config.empty() ? nlohmann::json()
                                                      : ReadJsonFile(options.engine_config),
                        dataset_identity, feature_files, DUSKMAP_VERSION, &manifest);
    CheckOutputFolder(output, *args, manifest);
    CreateFolder(output.string());
    // Held until the process ends: a second run into this folder is refused.
    const FolderLock lock(output);
    WriteRunManifest(manifest, output);

    // Parallelism comes from jobs; single-threaded OpenCV keeps per-frame
    // timings comparable with the paper's and the run deterministic.
    cv::setNumThreads(1);
    const std::map<std::string, int64_t> frames = FramesPerJob(plan, options, sessions);
    int64_t total_frames = 0;
    for (const auto& [id, n] : frames) total_frames += n;
    // (Said once the run is accepted: a refusal stays one line.)
    std::cout << "dataset: " << dataset_identity["files"].get<int64_t>() << " files, " << std::fixed
              << std::setprecision(2) << dataset_identity["bytes"].get<double>() / 1e9
              << " GB checksummed in " << std::setprecision(1) << checksum_s << " s\n"
              << std::defaultfloat;
    std::cout << "duskmap run: " << plan.jobs.size() << " jobs (" << total_frames
              << " frame passes), " << jobs << " at once, results in " << output.string()
              << (shard_count > 1 ? ", shard " + args->shard : std::string()) << "\n"
              << std::flush;

    const bool terminal = StdoutIsTerminal();
    int64_t frames_done = 0;
    const auto on_progress = [&](const JobRunProgress& p) {
      const auto it = frames.find(p.last_job_id);
      if (it != frames.end()) frames_done += it->second;
      const double rate = p.elapsed_s > 0 ? frames_done / p.elapsed_s : 0.0;
      const double eta =
          frames_done > 0 ? p.elapsed_s * (total_frames - frames_done) / frames_done : 0.0;
      std::ostringstream line;
      line << "[" << p.finished << "/" << p.total << " jobs" << (p.failed ? ", " : "")
           << (p.failed ? std::to_string(p.failed) + " failed" : "") << "] " << std::fixed
           << std::setprecision(1) << rate << " frames/s, elapsed " << FormatDuration(p.elapsed_s)
           << ", ETA " << FormatDuration(eta) << "  " << p.last_job_id;
      if (terminal) {
        std::cout << "\r\033[K" << line.str() << std::flush;
      } else {
        std::cout << line.str() << "\n" << std::flush;
      }
    };
    SharedFeatureCacheOptions shared_cache;
    if (!args->feature_cache.empty()) {
      shared_cache.folder = args->feature_cache;
      shared_cache.program_id = ProgramChecksum();
      shared_cache.dataset_identity = dataset_identity;
      shared_cache.file_checksums = feature_files;
    }
    EngineJobExecutor executor(options, engine, *dataset, output, shared_cache);
    JobRunnerOptions runner;
    runner.output_dir = output;
    runner.parallel_jobs = jobs;
    runner.resume = args->resume;
    const JobRunSummary summary = RunJobs(plan, executor, runner, on_progress);
    if (terminal) std::cout << "\n";

    std::cout << "done in " << FormatDuration(summary.wall_s) << ": " << summary.executed
              << " jobs run, " << summary.resumed << " resumed, " << summary.failures.size()
              << " failed; job time by kind:";
    for (const auto& [kind, seconds] : summary.busy_s_by_kind) {
      std::cout << " " << JobKindName(kind) << " " << std::fixed << std::setprecision(1)
                << seconds << " s";
    }
    std::cout << "\n";
    // The failures first: when the disk is full, writing timing.json throws
    // too, and the jobs' own reasons must not be lost behind it.
    for (const JobFailure& failure : summary.failures) {
      std::cout << "failed: " << failure.job_id << ": " << failure.message << "\n";
    }
    std::cout.flush();
    WriteRunTiming(summary, output / "timing.json");
    if (args->report && shard_count == 1) {
      const ExperimentReportRequest request =
          ReportRequestFor(args->config, {output}, output / "report", args->figures);
      PrintReportOutcome(request, WriteExperimentReport(request));
    }
    SLAM_THROW_IF_NOT(Error, summary.ok())
        << summary.failures.size() << " of " << plan.jobs.size() << " jobs failed (see above)";
    return 0;
  };
}

const bool kRegistered = RegisterCommand(
    {"run", "Run an experiment matrix (features x maps x sessions) and write its report",
     &SetupRun});

}  // namespace
}  // namespace duskmap::cli
