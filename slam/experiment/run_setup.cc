#include "slam/experiment/run_setup.h"

#include <algorithm>
#include <fstream>
#include <iterator>
#include <sstream>
#include <thread>

#include <opencv2/core.hpp>

#include "slam/core/check.h"
#include "slam/core/checksum.h"
#include "slam/core/json_fields.h"
#include "slam/core/timer.h"
#include "slam/datasets/dataset_factory.h"
#include "slam/datasets/dataset_identity.h"
#include "slam/experiment/engine_executor.h"
#include "slam/experiment/feature_files.h"
#include "slam/experiment/shared_feature_cache.h"
#include "slam/io/folder_commit.h"

namespace duskmap {
namespace fs = std::filesystem;
namespace {

// Frames each job processes, for the frames/s and ETA of the progress.
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
void CheckOutputFolder(const fs::path& output, const RunSetupOptions& options,
                       const RunManifest& manifest) {
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
  SLAM_THROW_IF_NOT(ConfigError, options.resume || options.overwrite)
      << output.string()
      << ": holds an earlier run; pass --resume to continue it or --overwrite to redo every job";
  if (!options.resume) return;
  CheckResumable(ReadRunManifest(output), manifest, output);
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

// The configs, the flags and where the run writes: outputs apart from the
// inputs, the shared feature cache outside the results. (The config files
// are read first: their errors come before the flags'.)
PreparedRun ReadRunConfigs(const RunSetupOptions& options) {
  PreparedRun run;
  run.options = ReadExperimentOptions(options.config_path);
  run.engine = run.options.engine_config.empty() ? EngineOptions()
                                                 : ReadEngineOptionsFile(run.options.engine_config);
  options.Check();
  run.shard = ParseShard(options.shard);
  run.output_dir = options.output_dir.empty()
                       ? fs::path("out") / fs::path(options.config_path).stem()
                       : options.output_dir;
  run.parallel_jobs = options.parallel_jobs > 0
                          ? options.parallel_jobs
                          : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  run.resume = options.resume;
  run.feature_cache = options.feature_cache;
  CheckOutputsApartFromInputs(
      {{"--output", run.output_dir.string()}, {"--feature-cache", options.feature_cache}},
      {{"config", options.config_path},
       {"engine_config", run.options.engine_config},
       {"dataset.path", run.options.dataset_path}});
  SLAM_THROW_IF_NOT(ConfigError, options.feature_cache.empty() ||
                                     !IsSameOrInside(options.feature_cache, run.output_dir))
      << "--feature-cache " << options.feature_cache << ": must lie outside --output "
      << run.output_dir.string() << " (an --overwrite of the results would remove it)";
  return run;
}

// The dataset opened, its sessions checked against the config, the
// runnable feature columns selected and this shard's plan.
void PlanRun(const RunSetupOptions& options,
             const std::function<void(const std::vector<SkippedFeature>&)>& on_features_selected,
             PreparedRun* run) {
  DatasetReadOptions read;
  read.allow_unordered = options.allow_unordered;
  run->dataset = OpenDataset(run->options.dataset_path, run->options.dataset_format, read);
  run->sessions = run->dataset->Sessions();
  std::vector<std::string> session_names;
  for (const SessionInfo& s : run->sessions) session_names.push_back(s.name);
  // A session the dataset lacks fails here, before any job runs.
  CheckSessionsExist(run->options, session_names, options.config_path);
  CheckDeclaredFeatureFiles(run->options);
  RunManifest& manifest = run->manifest;
  manifest.config_path = options.config_path;
  manifest.dataset_path = run->options.dataset_path;
  manifest.session_clock = SessionClockOf(run->sessions, run->options.session_clock_times);
  manifest.shard_index = run->shard.index;
  manifest.shard_count = run->shard.count;
  SelectRunnableFeatures(run->options,
                         {run->engine.features.superpoint.model_path,
                          run->engine.matcher.superglue.model_path},
                         &manifest);
  if (on_features_selected) on_features_selected(manifest.skipped_features);
  SLAM_THROW_IF_NOT(ConfigError, !manifest.features.empty())
      << options.config_path << ": every feature type was skipped";
  const ExperimentPlan full_plan = PlanFromManifest(run->options, manifest);
  run->plan = SelectShard(full_plan, run->shard.index, run->shard.count);
}

// Every file of the dataset and every model or h5 file is read once here:
// content, not size or time, decides what a resume or the feature cache
// reuses. Recorded in the manifest's configuration.
void ChecksumInputs(const RunSetupOptions& options, PreparedRun* run) {
  Stopwatch checksum_watch;
  run->dataset_identity =
      DatasetIdentity(run->options.dataset_path, run->options.dataset_format, run->sessions);
  run->dataset_identity["allow_unordered"] = options.allow_unordered;
  run->feature_files = RunFeatureFileChecksums(run->options, run->engine, run->manifest.features);
  run->checksum_s = checksum_watch.ElapsedMs() / 1e3;
  run->dataset_files = run->dataset_identity["files"].get<int64_t>();
  run->dataset_bytes = run->dataset_identity["bytes"].get<double>();
  SetRunConfiguration(ReadJsonFile(options.config_path),
                      run->options.engine_config.empty() ? nlohmann::json()
                                                         : ReadJsonFile(run->options.engine_config),
                      run->dataset_identity, run->feature_files, options.program_version,
                      &run->manifest);
}

}  // namespace

ShardSpec ParseShard(const std::string& text) {
  ShardSpec shard{-1, -1};
  char slash = 0;
  std::istringstream in(text);
  in >> shard.index >> slash >> shard.count;
  SLAM_THROW_IF_NOT(ConfigError, in && in.peek() == EOF && slash == '/' && shard.count >= 1 &&
                                     shard.index >= 0 && shard.index < shard.count)
      << "--shard " << text << ": expected i/n with 0 <= i < n";
  SLAM_THROW_IF_NOT(ConfigError, shard.count <= kMaxShardCount)
      << "--shard " << text << ": at most " << kMaxShardCount << " shards";
  return shard;
}

void RunSetupOptions::Check() const {
  ParseShard(shard);
  SLAM_THROW_IF_NOT(ConfigError, parallel_jobs >= 0 && parallel_jobs <= 4096)
      << "--jobs: must be in [0, 4096], got " << parallel_jobs;
  SLAM_THROW_IF_NOT(ConfigError, !(resume && overwrite))
      << "--resume and --overwrite: give one (continue the earlier run, or redo it)";
}

PreparedRun PrepareRun(const RunSetupOptions& options,
                       const std::function<void(const std::vector<SkippedFeature>&)>&
                           on_features_selected) {
  PreparedRun run = ReadRunConfigs(options);
  PlanRun(options, on_features_selected, &run);
  ChecksumInputs(options, &run);
  CheckOutputFolder(run.output_dir, options, run.manifest);
  CreateFolder(run.output_dir.string());
  run.lock = std::make_unique<FolderLock>(run.output_dir);
  WriteRunManifest(run.manifest, run.output_dir);
  run.frames_per_job = FramesPerJob(run.plan, run.options, run.sessions);
  for (const auto& [id, n] : run.frames_per_job) run.total_frames += n;
  return run;
}

JobRunSummary RunPreparedJobs(PreparedRun& run,
                              const std::function<void(const RunProgress&)>& on_progress) {
  // Parallelism comes from jobs; single-threaded OpenCV keeps per-frame
  // timings comparable with the paper's and the run deterministic.
  cv::setNumThreads(1);
  int64_t frames_done = 0;
  const auto progress = [&](const JobRunProgress& p) {
    const auto it = run.frames_per_job.find(p.last_job_id);
    if (it != run.frames_per_job.end()) frames_done += it->second;
    RunProgress report;
    report.jobs = p;
    report.frames_done = frames_done;
    report.frames_per_s = p.elapsed_s > 0 ? frames_done / p.elapsed_s : 0.0;
    report.eta_s =
        frames_done > 0 ? p.elapsed_s * (run.total_frames - frames_done) / frames_done : 0.0;
    if (on_progress) on_progress(report);
  };
  SharedFeatureCacheOptions shared_cache;
  if (!run.feature_cache.empty()) {
    shared_cache.folder = run.feature_cache;
    shared_cache.program_id = ProgramChecksum();
    shared_cache.dataset_identity = run.dataset_identity;
    shared_cache.file_checksums = run.feature_files;
  }
  EngineJobExecutor executor(run.options, run.engine, *run.dataset, run.output_dir, shared_cache);
  JobRunnerOptions runner;
  runner.output_dir = run.output_dir;
  runner.parallel_jobs = run.parallel_jobs;
  runner.resume = run.resume;
  return RunJobs(run.plan, executor, runner, progress);
}

void WriteRunTiming(const JobRunSummary& summary, const fs::path& path) {
  nlohmann::json json;
  json["wall_s"] = summary.wall_s;
  json["executed"] = summary.executed;
  json["resumed"] = summary.resumed;
  for (const auto& [kind, seconds] : summary.busy_s_by_kind) json["job_s_by_kind"][JobKindName(kind)] = seconds;
  json["job_s"] = summary.job_wall_s;
  WriteFileAtomically(path.string(), [&](std::ostream& out) { out << json.dump(1) << "\n"; });
}

}  // namespace duskmap
