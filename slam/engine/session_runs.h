// Drivers that run whole sessions through the engine: mapping several input
// sessions back to back into one map, and localizing one session against a
// map, with the summaries the CLI and the experiment runner report.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "slam/engine/engine_options.h"
#include "slam/engine/localization_evaluation.h"
#include "slam/engine/localizer.h"
#include "slam/engine/mapper.h"
#include "slam/io/dataset_reader.h"
#include "slam/map/map_memory.h"

namespace duskmap {

struct StageTimingSummary {
  double median_ms = 0.0;
  double mean_ms = 0.0;
  double max_ms = 0.0;
};

// Median, mean and max of a list of per-frame times (zeros when empty).
StageTimingSummary SummarizeTimes(std::vector<double> times_ms);

// A session's per-frame times, stage by stage (the paper's timing rows).
struct SessionStageTimings {
  StageTimingSummary features;
  StageTimingSummary loop_closure_detection;
  StageTimingSummary proximity_detection;
  StageTimingSummary transformation_estimation;
  StageTimingSummary optimisation;  // mapping only
  StageTimingSummary lcd_plus_te;   // localization only: LCD + TE of each frame
  StageTimingSummary total;
};

struct MapSummary {
  int num_sessions = 0;
  std::vector<int> nodes_per_session;                        // by session id
  std::map<std::string, int> links_by_type;                  // "odometry", "loop_closure", ...
  std::vector<std::vector<SessionId>> connected_groups;      // sessions joined by links
  size_t vocabulary_words = 0;
  MapMemory memory;
};

// JSON: ToJsonObject(summary) with session_runs_json.h.
MapSummary SummarizeMap(const Map& map);

// One session's frames as the engine drivers consume them. A source either
// hands out frames with their images (the engine extracts the features) or
// frames whose features were extracted earlier (cached, images left empty).
class FrameSource {
 public:
  virtual ~FrameSource() = default;
  virtual const SessionInfo& info() const = 0;
  // The next frame, or nullopt at the end. When the source has the frame's
  // features it stores them in `*features`, otherwise it resets it.
  virtual std::optional<RgbdFrame> Next(std::optional<FrameFeatures>* features) = 0;
};

// A FrameSource over a dataset session: frames with images, no features.
class ReaderFrameSource : public FrameSource {
 public:
  explicit ReaderFrameSource(std::unique_ptr<SessionReader> reader);
  const SessionInfo& info() const override { return reader_->info(); }
  std::optional<RgbdFrame> Next(std::optional<FrameFeatures>* features) override;

 private:
  std::unique_ptr<SessionReader> reader_;
};

struct MappingRun {
  Map map;
  // What the finished map needs for localization, as LocalizationRun::memory,
  // with the mapper's vocabulary and Bayes filter standing in for the
  // localizer's (both hold the map's words and places).
  MapMemory memory;
  std::vector<MappingFrameResult> frames;
  SessionStageTimings timings;
  // Building the vocabulary index stored with the map (vocabulary_index.h),
  // part of wall_s.
  double index_build_s = 0.0;
  double wall_s = 0.0;
};

// Replays `sessions` of `dataset` (in order) into one map.
MappingRun BuildMap(const DatasetReader& dataset, const std::vector<std::string>& sessions,
                    const EngineOptions& options);
// Replays the sources (in order, each its own session) into one map.
MappingRun BuildMap(const std::vector<FrameSource*>& sessions, const EngineOptions& options);

struct LocalizationRun {
  std::vector<LocalizationRecord> records;
  // What the map needs for localization: descriptors, keypoints + 3D points
  // and graph from the map; words + index from the localizer's vocabulary;
  // filter = the Bayes filter's transition columns + one posterior per place.
  MapMemory memory;
  LocalizationSummary summary;
  SessionStageTimings timings;
  // How the localizer's vocabulary index was obtained: restored from the
  // map's stored index, or built (with the reason), and how long it took.
  IndexRestore index_restore;
  double setup_s = 0.0;  // the localizer's construction (index restore included)
  double wall_s = 0.0;
};

// Localizes every frame of `session` against `map` (read-only) and evaluates
// the re-localizations where the frames have ground truth.
LocalizationRun LocalizeSession(const Map& map, SessionReader& session,
                                const EngineOptions& options,
                                const RelocalizationMetricsOptions& metrics = {});
// The same over a frame source read from its current position to its end.
LocalizationRun LocalizeSession(const Map& map, FrameSource& session,
                                const EngineOptions& options,
                                const RelocalizationMetricsOptions& metrics = {});
// The same for a map loaded without its words (MapLoadOptions::load_words
// false): the localizer imports `words`, which are released before the first
// frame, so the run holds the words once, in the vocabulary's index.
LocalizationRun LocalizeSession(const Map& map, MapWords words, FrameSource& session,
                                const EngineOptions& options,
                                const RelocalizationMetricsOptions& metrics = {});
LocalizationRun LocalizeSession(const Map& map, MapWords words, SessionReader& session,
                                const EngineOptions& options,
                                const RelocalizationMetricsOptions& metrics = {});

}  // namespace duskmap
