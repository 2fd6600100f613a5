// run.json: what one `duskmap run` covered, written into its results folder
// before any job runs, so that `duskmap report` can rebuild the same plan
// from the results alone (on another machine, without the dataset): the
// feature columns that ran and those skipped (and why), each session's clock
// time, and the shard.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "slam/experiment/experiment_config.h"
#include "slam/experiment/job_plan.h"
#include "slam/experiment/session_clock.h"
#include "slam/io/dataset_reader.h"

namespace duskmap {

struct SkippedFeature {
  std::string label;
  std::string reason;
};

// More shards than any plan has jobs: a run.json or --shard beyond it is refused
// before anything is sized by it.
inline constexpr int kMaxShardCount = 100000;

struct RunManifest {
  std::string config_path;
  std::string dataset_path;
  std::vector<std::string> features;        // columns that ran
  std::vector<SkippedFeature> skipped_features;
  SessionClock session_clock;               // minutes since midnight, by session name
  int shard_index = 0;
  int shard_count = 1;  // in [1, kMaxShardCount]
  // Everything that shapes a result, for --resume: the experiment config and
  // the engine config as parsed (RunConfiguration), the dataset's identity
  // (DatasetIdentity) and the duskmap version; and its checksum.
  nlohmann::json configuration;
  std::string configuration_checksum;
};

// The `configuration` record of a run: {"experiment": <config JSON>,
// "engine": <engine config JSON, or null for the paper defaults>,
// "dataset": <identity, with its sessions' content checksums>,
// "feature_files": <{path: checksum} of the model and h5 files the columns
// read (RunFeatureFileChecksums)>, "duskmap": <version>} and its checksum
// into manifest->configuration_checksum.
void SetRunConfiguration(const nlohmann::json& experiment, const nlohmann::json& engine,
                         const nlohmann::json& dataset_identity,
                         const nlohmann::json& feature_files, const std::string& version,
                         RunManifest* manifest);

// The first place where two JSON values differ, as "key.path[2].key (earlier
// X, now Y)" ("the top level (...)" for two different non-containers), or ""
// when they are equal. Object keys are compared in sorted order.
std::string FirstJsonDifference(const nlohmann::json& earlier, const nlohmann::json& now);

// Throws ConfigError naming run.json when `earlier` (the folder's manifest)
// cannot be resumed by `now`: other features, sessions or shard, or another
// configuration (the first differing key named), or no configuration record.
// Changed data is said in words: "the files of session A (images, depth maps
// or metadata) changed since the earlier run" (one of them rewritten, even
// with the same size), the shared files, or "the feature file X changed".
void CheckResumable(const RunManifest& earlier, const RunManifest& now,
                    const std::filesystem::path& results_dir);

// Clock time of every dataset session that has one; `configured` (the
// experiment config's session_clock_times) adds or overrides times by name.
SessionClock SessionClockOf(const std::vector<SessionInfo>& sessions,
                            const std::map<std::string, std::string>& configured = {});

// The model files the feature columns need (empty = not configured).
struct FeatureModels {
  std::string superpoint;  // features.superpoint.model_path (SP and SG)
  std::string superglue;   // matcher.superglue.model_path (SG)
};

// Splits the configured feature columns into those that can run with these
// models and those skipped (SuperPoint without its model, SuperGlue without
// either), each with the reason.
void SelectRunnableFeatures(const ExperimentOptions& options, const FeatureModels& models,
                            RunManifest* manifest);

void WriteRunManifest(const RunManifest& manifest, const std::filesystem::path& results_dir);
// Throws InputError naming the file when run.json is missing or malformed.
RunManifest ReadRunManifest(const std::filesystem::path& results_dir);

// The plan of the manifest's features (all shards, for reports).
ExperimentPlan PlanFromManifest(ExperimentOptions options, const RunManifest& manifest);

}  // namespace duskmap
