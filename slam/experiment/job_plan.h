// Expands an experiment into jobs (feature extraction per session, map
// building, localization of one session on one map) and records which job
// fills which cell of the paper's tables. Jobs are listed dependencies first,
// in a deterministic order, and can be split into shards for batch schedulers.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "slam/experiment/experiment_config.h"
#include "slam/experiment/session_clock.h"

namespace duskmap {

enum class JobKind { kExtract, kBuildMap, kLocalize };

const char* JobKindName(JobKind kind);

struct Job {
  JobKind kind = JobKind::kExtract;
  // Unique and usable as a relative file path: "extract/sift/1",
  // "map/SI/1+3+5", "localize/SI/1+3+5/A".
  std::string id;
  std::string feature;    // FeatureSetup label (map and localize jobs)
  std::string extractor;  // the feature cache's name, setup.CacheName() (every job)
  // The column the job runs (its extractor, a declared column's file or
  // model, its matcher); an extract job's is the first listed column that
  // extracts its cache (columns sharing a cache differ only in the matcher).
  FeatureSetup setup;
  MapSpec map;            // map and localize jobs: the map built or used
  std::string session;    // extract and localize jobs
  std::vector<std::string> depends_on;  // ids of jobs that must finish first
};

// One cell of the re-localization matrix: localization session `session` on
// the map row `row` (as reported, e.g. "1|2|3|4|5|6") comes from job `job_id`.
struct MatrixCell {
  std::string feature;
  std::string row;
  std::string session;
  std::string job_id;
};

struct ConsecutiveCell {
  std::string feature;
  std::string map_session;
  std::string localization_session;
  int gap_min = 0;        // clock-time difference in minutes
  int gap_class_min = 0;  // nearest of ExperimentOptions::consecutive_gap_classes_min
  std::string job_id;
};

struct ExperimentPlan {
  std::vector<Job> jobs;  // dependencies before dependants
  std::vector<MatrixCell> cells;
  std::vector<ConsecutiveCell> consecutive;

  const Job* FindJob(const std::string& id) const;
};

// Throws ConfigError when a session needed for closest-in-time maps or
// consecutive pairs has no clock time.
ExperimentPlan PlanExperiment(const ExperimentOptions& options, const SessionClock& clock);

// The jobs of shard `index` of `count` (0-based): every built map with all the
// localization jobs on it goes to exactly one shard (round robin over maps in
// plan order), with the extraction jobs it needs. Cells are kept only for jobs
// in the shard. Throws ConfigError for an invalid index/count.
ExperimentPlan SelectShard(const ExperimentPlan& plan, int index, int count);

}  // namespace duskmap
