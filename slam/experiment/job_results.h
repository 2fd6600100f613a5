// What the jobs of an experiment leave behind for the report: one summary per
// extract job, per localization job and per map job, stored as summary.json in the job's
// folder. Per-frame records stay in the job folder (frames.jsonl) for figures.
// `duskmap localize --summary` writes the same localization summary.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace duskmap {

class Map;
struct LocalizationRun;
struct MapMemory;
struct SessionStageTimings;

// Mean per-frame time of each stage, milliseconds.
struct StageTimesMs {
  double features = 0.0;
  double loop_closure_detection = 0.0;
  double proximity_detection = 0.0;
  double transformation_estimation = 0.0;
  double optimisation = 0.0;
  double total = 0.0;
};

struct LocalizationJobSummary {
  int num_frames = 0;
  int num_relocalized = 0;
  int num_no_candidate = 0;  // frames for which neither LCD nor PD proposed a node
  // Re-localizations within 0.25 m/2°, 0.5 m/5°, 5 m/10° of ground truth
  // (all zero and has_ground_truth false when the session has none).
  bool has_ground_truth = false;
  std::array<int, 3> num_within_threshold{};
  int num_wrong = 0;  // re-localized outside the default threshold (0.5 m/5°)
  double mean_inliers_pct = 0.0;  // mean over re-localized frames of 100 * inliers / features
  double mean_jump_mm = 0.0;      // mean correction change at re-localizations
  double mean_features = 0.0;     // features per frame
  double max_gap_m = 0.0;         // largest distance travelled without re-localization
  int num_within_55cm = 0;        // re-localized within 0.55 m of the previous one
  // num_within_55cm had every frame re-localized (GapMetrics::num_within_bound):
  // the path's bound; -1 in summaries written before it was recorded.
  int num_within_55cm_bound = -1;
  // Session name of the map node each re-localized frame matched, per frame
  // ("" when not re-localized), for the over-time figure.
  std::vector<std::string> matched_session_per_frame;
  StageTimesMs mean_times_ms;
  double median_lcd_te_ms = 0.0;  // median per frame of LCD + transformation estimation
  // What the localizer held, per component (descriptors, keypoints_points,
  // words_index: the map's words and the imported vocabulary, graph, filter).
  std::map<std::string, size_t> memory_bytes;
  // Before the first frame: loading the map (0 when another job on the
  // same map had loaded it: map_from_cache), and building the localizer,
  // of which restoring (or, without a stored index, building) its
  // vocabulary index. Summaries written before these existed read as 0.
  double map_load_s = 0.0;
  bool map_from_cache = false;
  double localizer_setup_s = 0.0;
  double index_restore_s = 0.0;
  bool index_restored = false;
  std::string index_rebuild_reason;  // "" when restored
};

// Per-frame extraction time of an extract job, milliseconds.
struct ExtractionTimesMs {
  double median = 0.0;
  double mean = 0.0;
  double max = 0.0;
};

// An extract job's summary; a feature cache kept across runs stores it with
// the features (shared_feature_cache.h) and a restored job writes it again.
struct ExtractJobSummary {
  std::string extractor;  // the feature cache's name (Job::extractor)
  std::string session;
  int64_t frames = 0;          // frames in the cache
  double mean_features = 0.0;  // features per frame
  ExtractionTimesMs extraction_ms;
  // "stored <key>" or "restored <key>" with a cache kept across runs; "" without.
  std::string shared_cache;
};

struct MapJobSummary {
  int num_nodes = 0;
  std::map<std::string, int> nodes_per_session;
  std::map<std::string, int> links_per_type;  // "odometry", "loop_closure", ...
  int num_connected_components = 0;           // sessions groups joined by links
  int vocabulary_words = 0;
  size_t descriptor_bytes_per_feature = 0;
  std::map<std::string, size_t> memory_bytes;  // per component, for localization
  double ate_mm = -1.0;                        // vs ground truth; < 0 when unknown
  double mean_features = 0.0;
  StageTimesMs mean_times_ms;
  double build_wall_s = 0.0;
  double index_build_s = 0.0;  // the stored vocabulary index, part of build_wall_s
};

// Their JSON form (keys, and which older summaries lack): job_results_json.h.

// The mean per-frame time of each stage of `timings`.
StageTimesMs MeanStageTimes(const SessionStageTimings& timings);
// MapMemory's components by their JSON keys (the summaries' memory_bytes).
std::map<std::string, size_t> MemoryBytesByComponent(const MapMemory& memory);
// The summary of the localization of one session on `map`, but for how the
// map was had (map_load_s, map_from_cache), which only the caller knows. The
// mean times are the run's: it counts no time for features it did not
// extract (read from a feature cache).
LocalizationJobSummary SummarizeLocalization(const Map& map, const LocalizationRun& run);

// Writes summary.json into job_dir / reads it back; reading throws InputError
// naming the file when it is missing or malformed.
void WriteSummary(const std::filesystem::path& job_dir, const nlohmann::json& summary);
nlohmann::json ReadSummary(const std::filesystem::path& job_dir);

// A job's summary.json (ReadSummary) as its typed summary.
// InputError naming the file for a key that is unknown, of the wrong type, or
// missing (the keys added later read as their defaults when absent).
LocalizationJobSummary ReadLocalizationJobSummary(const std::filesystem::path& job_dir);
MapJobSummary ReadMapJobSummary(const std::filesystem::path& job_dir);
ExtractJobSummary ReadExtractJobSummary(const std::filesystem::path& job_dir);

}  // namespace duskmap
