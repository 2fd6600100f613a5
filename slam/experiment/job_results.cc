#include "slam/experiment/job_results.h"

#include <fstream>
#include <string>
#include <system_error>
#include <type_traits>
#include <utility>

#include "slam/core/check.h"
#include "slam/core/json_fields.h"
#include "slam/engine/session_runs.h"
#include "slam/experiment/job_results_json.h"
#include "slam/map/map_memory_json.h"

namespace duskmap {
namespace {

template <typename T, typename = void>
struct HasRequiredKeys : std::false_type {};
template <typename T>
struct HasRequiredKeys<T, std::void_t<decltype(JsonCodec<T>::VisitRequired(
                              std::declval<int&>(), std::declval<const T&>()))>>
    : std::true_type {};

// Visits the keys a summary must hold (its codec's VisitRequired, or every
// key of a codec without one), nested summaries included; throws
// ConfigError "<where>: missing key 'k'" at the first one `object` lacks.
class RequiredKeyCheck {
 public:
  RequiredKeyCheck(const nlohmann::json& object, std::string where)
      : object_(object), where_(std::move(where)) {}

  template <typename T>
  static void Run(const nlohmann::json& object, const std::string& where, const T& value) {
    RequiredKeyCheck check(object, where);
    if constexpr (HasRequiredKeys<T>::value) {
      JsonCodec<T>::VisitRequired(check, value);
    } else {
      JsonCodec<T>::Visit(check, value);
    }
  }

  template <typename T>
  void operator()(const char* key, const T& value) {
    SLAM_THROW_IF_NOT(ConfigError, object_.contains(key)) << where_ << ": missing key '" << key << "'";
    if constexpr (json_codec_internal::HasCodec<T>::value) {
      Run(object_.at(key), where_ + "." + key, value);
    }
  }

 private:
  const nlohmann::json& object_;
  std::string where_;
};

// The typed summary in job_dir/summary.json: read strictly by its codec, then
// checked for the keys every summary holds.
template <typename T>
T ReadJobSummary(const std::filesystem::path& job_dir) {
  const std::string path = (job_dir / "summary.json").string();
  const nlohmann::json json = ReadSummary(job_dir);
  try {
    SLAM_THROW_IF_NOT(ConfigError, json.is_object())
        << path << ": expected an object, got " << json.type_name();
    T summary = ReadJsonOptions<T>(json, path);
    RequiredKeyCheck::Run(json, path, summary);
    return summary;
  } catch (const ConfigError& e) {
    SLAM_THROW(InputError) << e.what() << " (malformed job summary)";
  }
  return T();  // not reached
}

}  // namespace

StageTimesMs MeanStageTimes(const SessionStageTimings& timings) {
  StageTimesMs times;
  times.features = timings.features.mean_ms;
  times.loop_closure_detection = timings.loop_closure_detection.mean_ms;
  times.proximity_detection = timings.proximity_detection.mean_ms;
  times.transformation_estimation = timings.transformation_estimation.mean_ms;
  times.optimisation = timings.optimisation.mean_ms;
  times.total = timings.total.mean_ms;
  return times;
}

std::map<std::string, size_t> MemoryBytesByComponent(const MapMemory& memory) {
  return ToJsonObject(memory).get<std::map<std::string, size_t>>();
}

LocalizationJobSummary SummarizeLocalization(const Map& map, const LocalizationRun& run) {
  LocalizationJobSummary summary;
  const RelocalizationSummary& r = run.summary.relocalization;
  summary.num_frames = r.num_frames;
  summary.num_relocalized = r.num_relocalized;
  summary.has_ground_truth = run.summary.evaluated;
  summary.num_within_threshold = r.num_within;
  summary.num_wrong = r.num_wrong;
  summary.mean_jump_mm = run.summary.mean_jump_mm;
  summary.max_gap_m = run.summary.gaps.max_gap_m;
  summary.num_within_55cm = run.summary.gaps.num_within;
  summary.num_within_55cm_bound = run.summary.gaps.num_within_bound;
  double inliers_pct_sum = 0.0;
  double features_sum = 0.0;
  for (const LocalizationRecord& record : run.records) {
    features_sum += record.num_features;
    if (record.outcome == LocalizationOutcome::kNoCandidate ||
        (record.outcome == LocalizationOutcome::kBadSignature && record.proximity_candidates == 0)) {
      ++summary.num_no_candidate;
    }
    if (record.relocalized) {
      if (record.num_features > 0) inliers_pct_sum += 100.0 * record.inliers / record.num_features;
      summary.matched_session_per_frame.push_back(map.sessions()[record.matched_session].name);
    } else {
      summary.matched_session_per_frame.emplace_back();
    }
  }
  summary.mean_inliers_pct = r.num_relocalized > 0 ? inliers_pct_sum / r.num_relocalized : 0.0;
  summary.mean_features = run.records.empty() ? 0.0 : features_sum / run.records.size();
  summary.mean_times_ms = MeanStageTimes(run.timings);
  summary.median_lcd_te_ms = run.timings.lcd_plus_te.median_ms;
  summary.memory_bytes = MemoryBytesByComponent(run.memory);
  summary.localizer_setup_s = run.setup_s;
  summary.index_restore_s = run.index_restore.seconds;
  summary.index_restored = run.index_restore.restored;
  summary.index_rebuild_reason = run.index_restore.rebuild_reason;
  return summary;
}

void WriteSummary(const std::filesystem::path& job_dir, const nlohmann::json& summary) {
  const std::filesystem::path path = job_dir / "summary.json";
  std::ofstream out(path);
  out << summary.dump(1) << "\n";
  SLAM_THROW_IF_NOT(InputError, out.good()) << path.string() << ": cannot write";
}

nlohmann::json ReadSummary(const std::filesystem::path& job_dir) {
  const std::filesystem::path path = job_dir / "summary.json";
  std::error_code error;
  SLAM_THROW_IF_NOT(InputError, std::filesystem::exists(path, error))
      << path.string() << ": missing job summary";
  try {
    return ReadJsonFile(path.string());
  } catch (const ConfigError& e) {
    SLAM_THROW(InputError) << e.what() << " (malformed job summary)";
  }
  return nlohmann::json();  // not reached
}

LocalizationJobSummary ReadLocalizationJobSummary(const std::filesystem::path& job_dir) {
  return ReadJobSummary<LocalizationJobSummary>(job_dir);
}

MapJobSummary ReadMapJobSummary(const std::filesystem::path& job_dir) {
  return ReadJobSummary<MapJobSummary>(job_dir);
}

ExtractJobSummary ReadExtractJobSummary(const std::filesystem::path& job_dir) {
  return ReadJobSummary<ExtractJobSummary>(job_dir);
}

}  // namespace duskmap
