// The setup and the jobs of `duskmap run`: the configs read, the dataset
// opened and checksummed, the manifest (run.json) and this shard's plan,
// the results folder checked, locked and its run.json written; then the
// plan's jobs run on the engine-backed executor with the feature caches.
// Prints nothing: the notes and the progress come back through callbacks
// and typed results for the CLI to print.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "slam/core/rgbd_frame.h"
#include "slam/engine/engine_options.h"
#include "slam/experiment/experiment_config.h"
#include "slam/experiment/job_plan.h"
#include "slam/experiment/job_runner.h"
#include "slam/experiment/run_manifest.h"
#include "slam/io/dataset_reader.h"
#include "slam/io/output_safety.h"

namespace duskmap {

struct RunSetupOptions {
  std::string config_path;           // the experiment config
  std::filesystem::path output_dir;  // results folder; empty = out/<config name without .json>
  int parallel_jobs = 0;             // jobs run at once, in [0, 4096]; 0 = one per hardware thread
  bool resume = false;               // continue the run in output_dir, keeping finished jobs
  bool overwrite = false;            // redo every job of the run in output_dir
  std::string shard = "0/1";         // shard i of n, "i/n" with 0 <= i < n
  bool allow_unordered = false;      // read rgb.txt/depth.txt as recorded (real TUM recordings)
  std::string feature_cache;         // folder of feature caches kept across runs; empty = none
  std::string program_version;       // recorded in run.json; a resume must match it

  // ConfigError naming the flag: shard, parallel_jobs, resume with overwrite.
  void Check() const;
};

struct ShardSpec {
  int index = 0;
  int count = 1;
};

// "i/n" with 0 <= i < n; ConfigError naming --shard otherwise.
ShardSpec ParseShard(const std::string& text);

struct PreparedRun {
  ExperimentOptions options;
  EngineOptions engine;
  std::filesystem::path output_dir;  // resolved (the default filled in)
  ShardSpec shard;
  int parallel_jobs = 1;             // resolved (>= 1)
  bool resume = false;
  std::string feature_cache;
  std::unique_ptr<DatasetReader> dataset;
  std::vector<SessionInfo> sessions;
  RunManifest manifest;              // as written to output_dir/run.json
  ExperimentPlan plan;               // this shard's jobs
  // The dataset's identity (DatasetIdentity, with how it was read) and the
  // checksums of the model or h5 files the columns read: the keys of the
  // shared feature cache.
  nlohmann::json dataset_identity;
  nlohmann::json feature_files;
  int64_t dataset_files = 0;         // files checksummed
  double dataset_bytes = 0.0;        // their bytes
  double checksum_s = 0.0;           // time spent checksumming them and the feature files
  std::map<std::string, int64_t> frames_per_job;  // frames each job processes, by id
  int64_t total_frames = 0;
  // Held until the run is destroyed: a second run into output_dir is refused.
  std::unique_ptr<FolderLock> lock;
};

// Reads the configs, checks `options`, opens the dataset, selects the
// runnable feature columns (`on_features_selected` gets the skipped ones,
// before a run whose every column was skipped is refused), plans, checksums
// the dataset and the feature files, checks the results folder (new, empty,
// or an earlier run with resume or overwrite), creates and locks it and
// writes run.json. Throws ConfigError/InputError naming the file or flag.
PreparedRun PrepareRun(const RunSetupOptions& options,
                       const std::function<void(const std::vector<SkippedFeature>&)>&
                           on_features_selected = {});

struct RunProgress {
  JobRunProgress jobs;
  int64_t frames_done = 0;    // frames of the finished jobs
  double frames_per_s = 0.0;  // since the run began
  double eta_s = 0.0;         // at that rate, for the frames left
};

// Runs the plan's jobs (OpenCV single-threaded: the parallelism comes from
// the jobs, and per-frame timings stay comparable with the paper's);
// `on_progress` is called after each job, serialised.
JobRunSummary RunPreparedJobs(PreparedRun& run,
                              const std::function<void(const RunProgress&)>& on_progress = {});

// Wall-clock times of this invocation (not deterministic, kept out of the
// report's tables): total, summed job time per kind, each job's time.
void WriteRunTiming(const JobRunSummary& summary, const std::filesystem::path& path);

}  // namespace duskmap
