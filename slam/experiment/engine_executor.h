// Runs the experiment's jobs on the SLAM engine:
//   extract   reads one dataset session (every frame_step-th frame, at most
//             max_frames_per_session) and writes its feature cache, or
//             restores it from a feature cache shared across runs;
//   map       replays the cached sessions of a map into one map (graph
//             reduction for "1-2-3-4-5-6" maps), saves map.db, its summary,
//             the per-frame mapping records and the graph for the figures;
//   localize  re-localizes one cached session on a saved map and writes the
//             per-frame records, the corrected trajectory and the summary;
//             the jobs on one map share its loaded copy (loaded_map_cache.h).
// Jobs only share files, so any number can run at once.
#pragma once

#include <filesystem>
#include <memory>
#include <mutex>
#include <string>

#include "slam/engine/engine_options.h"
#include "slam/experiment/experiment_config.h"
#include "slam/experiment/job_runner.h"
#include "slam/experiment/loaded_map_cache.h"
#include "slam/experiment/shared_feature_cache.h"
#include "slam/io/dataset_reader.h"

namespace duskmap {

// File names inside job folders.
inline constexpr const char* kFeatureCacheFile = "features.bin";
inline constexpr const char* kMapFile = "map.db";
inline constexpr const char* kFramesFile = "frames.jsonl";
inline constexpr const char* kGraphFile = "graph.csv";
inline constexpr const char* kTrajectoryFile = "trajectory.txt";

// The engine options of one feature column: the experiment's base options
// with the column's extractor (and matcher). Throws ConfigError when the
// column needs a model file the options do not name.
EngineOptions EngineOptionsForFeature(const EngineOptions& base, const FeatureSetup& setup);

class EngineJobExecutor : public JobExecutor {
 public:
  // `dataset` must outlive the executor; `output_dir` is the runner's;
  // `shared_cache` (no folder: none) keeps extracted features across runs.
  EngineJobExecutor(const ExperimentOptions& experiment, const EngineOptions& engine,
                    const DatasetReader& dataset, std::filesystem::path output_dir,
                    SharedFeatureCacheOptions shared_cache = {});

  void Execute(const Job& job, const std::filesystem::path& job_dir) override;

 private:
  void Extract(const Job& job, const std::filesystem::path& job_dir);
  void BuildMapJob(const Job& job, const std::filesystem::path& job_dir);
  void Localize(const Job& job, const std::filesystem::path& job_dir);
  // Mean per-frame extraction time of a session, from its extract job.
  double ExtractionMeanMs(const std::string& extractor, const std::string& session) const;
  std::filesystem::path CacheFile(const std::string& extractor, const std::string& session) const;

  ExperimentOptions experiment_;
  EngineOptions engine_;
  const DatasetReader& dataset_;
  std::filesystem::path output_dir_;
  std::mutex dataset_mutex_;  // serialises OpenSession
  LoadedMapCache maps_{2};    // maps of the localization jobs running now
  SharedFeatureCache shared_cache_;
};

}  // namespace duskmap
