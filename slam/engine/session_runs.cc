#include "slam/engine/session_runs.h"

#include <algorithm>
#include <numeric>
#include <utility>

#include "slam/core/check.h"
#include "slam/core/timer.h"
#include "slam/engine/vocabulary_index.h"

namespace duskmap {

StageTimingSummary SummarizeTimes(std::vector<double> times_ms) {
  StageTimingSummary s;
  if (times_ms.empty()) return s;
  std::sort(times_ms.begin(), times_ms.end());
  const size_t n = times_ms.size();
  s.median_ms = n % 2 ? times_ms[n / 2] : 0.5 * (times_ms[n / 2 - 1] + times_ms[n / 2]);
  s.mean_ms = std::accumulate(times_ms.begin(), times_ms.end(), 0.0) / n;
  s.max_ms = times_ms.back();
  return s;
}

namespace {

// Each stage's per-frame times, as SessionStageTimings summarizes them.
struct StageTimeLists {
  std::vector<double> features, loop_closure_detection, proximity_detection,
      transformation_estimation, optimisation, lcd_plus_te, total;
  SessionStageTimings Summarize() const {
    return {SummarizeTimes(features),     SummarizeTimes(loop_closure_detection),
            SummarizeTimes(proximity_detection), SummarizeTimes(transformation_estimation),
            SummarizeTimes(optimisation), SummarizeTimes(lcd_plus_te),
            SummarizeTimes(total)};
  }
};

}  // namespace

MapSummary SummarizeMap(const Map& map) {
  MapSummary s;
  s.num_sessions = static_cast<int>(map.sessions().size());
  s.nodes_per_session.assign(map.sessions().size(), 0);
  for (const auto& [id, node] : map.nodes()) ++s.nodes_per_session[node.session];
  for (const auto& [key, link] : map.links()) ++s.links_by_type[LinkTypeName(link.type)];
  s.connected_groups = map.ConnectedSessionGroups();
  s.vocabulary_words = map.words().ids.size();
  s.memory = ComputeMapMemory(map);
  return s;
}

ReaderFrameSource::ReaderFrameSource(std::unique_ptr<SessionReader> reader)
    : reader_(std::move(reader)) {
  SLAM_CHECK(reader_ != nullptr);
}

std::optional<RgbdFrame> ReaderFrameSource::Next(std::optional<FrameFeatures>* features) {
  features->reset();
  return reader_->Next();
}

MappingRun BuildMap(const DatasetReader& dataset, const std::vector<std::string>& sessions,
                    const EngineOptions& options) {
  std::vector<std::unique_ptr<FrameSource>> sources;
  std::vector<FrameSource*> pointers;
  for (const std::string& name : sessions) {
    sources.push_back(std::make_unique<ReaderFrameSource>(dataset.OpenSession(name)));
    pointers.push_back(sources.back().get());
  }
  return BuildMap(pointers, options);
}

MappingRun BuildMap(const std::vector<FrameSource*>& sessions, const EngineOptions& options) {
  SLAM_THROW_IF_NOT(InputError, !sessions.empty()) << "BuildMap: no session to map";
  Stopwatch wall;
  MappingRun run;
  StageTimeLists times;
  {  // the mapper is gone before the map's vocabulary index is built
    Mapper mapper(options);
    std::optional<FrameFeatures> features;
    for (FrameSource* source : sessions) {
      mapper.StartSession(source->info().name, source->info().clock_time);
      while (std::optional<RgbdFrame> frame = source->Next(&features)) {
        MappingFrameResult result = features ? mapper.ProcessFrame(*frame, std::move(*features))
                                             : mapper.ProcessFrame(*frame);
        times.features.push_back(result.timings.features_ms);
        times.loop_closure_detection.push_back(result.timings.lcd_ms);
        times.proximity_detection.push_back(result.timings.proximity_ms);
        times.transformation_estimation.push_back(result.timings.registration_ms);
        times.optimisation.push_back(result.timings.optimization_ms);
        times.total.push_back(result.timings.total_ms);
        run.frames.push_back(result);
      }
    }
    run.map = mapper.Finish();
    const LoopClosureDetector& lcd = mapper.loop_closure();
    run.memory = ComputeMapMemory(
        run.map, lcd.filter().TransitionBytes() + lcd.filter().num_places() * sizeof(double));
    // The mapper's live vocabulary, besides the words the map stores.
    run.memory.words_index_bytes += lcd.vocabulary().MemoryBytes();
  }
  run.timings = times.Summarize();
  run.index_build_s = StoreVocabularyIndex(options, &run.map);
  run.wall_s = wall.ElapsedMs() / 1000.0;
  return run;
}

namespace {

// Borrows a SessionReader as a FrameSource (frames with images).
class BorrowedReaderSource : public FrameSource {
 public:
  explicit BorrowedReaderSource(SessionReader& reader) : reader_(reader) {}
  const SessionInfo& info() const override { return reader_.info(); }
  std::optional<RgbdFrame> Next(std::optional<FrameFeatures>* features) override {
    features->reset();
    return reader_.Next();
  }

 private:
  SessionReader& reader_;
};

}  // namespace

LocalizationRun LocalizeSession(const Map& map, SessionReader& session,
                                const EngineOptions& options,
                                const RelocalizationMetricsOptions& metrics) {
  return LocalizeSession(map, MapWords(), session, options, metrics);
}

LocalizationRun LocalizeSession(const Map& map, MapWords words, SessionReader& session,
                                const EngineOptions& options,
                                const RelocalizationMetricsOptions& metrics) {
  session.Rewind();
  BorrowedReaderSource source(session);
  return LocalizeSession(map, std::move(words), source, options, metrics);
}

LocalizationRun LocalizeSession(const Map& map, FrameSource& session,
                                const EngineOptions& options,
                                const RelocalizationMetricsOptions& metrics) {
  return LocalizeSession(map, MapWords(), session, options, metrics);
}

LocalizationRun LocalizeSession(const Map& map, MapWords words, FrameSource& session,
                                const EngineOptions& options,
                                const RelocalizationMetricsOptions& metrics) {
  Stopwatch wall;
  Localizer localizer(map, options, words.ids.empty() ? nullptr : &words);
  words = MapWords();  // imported: the vocabulary's index holds them now
  LocalizationRun run;
  run.setup_s = wall.ElapsedMs() / 1000.0;
  run.index_restore = localizer.loop_closure().vocabulary().index_restore();
  std::vector<std::optional<Rigid3d>> truth;
  std::vector<Eigen::Vector3d> positions;
  StageTimeLists times;
  std::optional<FrameFeatures> features;
  while (std::optional<RgbdFrame> frame = session.Next(&features)) {
    LocalizationRecord record = features ? localizer.ProcessFrame(*frame, *features)
                                         : localizer.ProcessFrame(*frame);
    truth.push_back(frame->world_from_camera);
    positions.push_back(frame->odom_from_camera().translation);
    times.features.push_back(record.timings.features_ms);
    times.loop_closure_detection.push_back(record.timings.lcd_ms);
    times.proximity_detection.push_back(record.timings.proximity_ms);
    times.transformation_estimation.push_back(record.timings.registration_ms);
    times.lcd_plus_te.push_back(record.timings.lcd_ms + record.timings.registration_ms);
    times.total.push_back(record.timings.total_ms);
    run.records.push_back(std::move(record));
  }
  run.summary = EvaluateLocalization(map, truth, positions, metrics, &run.records);
  const LoopClosureDetector& lcd = localizer.loop_closure();
  run.memory = ComputeMapMemory(
      map, lcd.filter().TransitionBytes() + lcd.filter().num_places() * sizeof(double));
  // The imported vocabulary (words, index, inverted index), besides what the
  // map holds (its stored words only when it was loaded with them).
  run.memory.words_index_bytes += lcd.vocabulary().MemoryBytes();
  run.timings = times.Summarize();
  run.wall_s = wall.ElapsedMs() / 1000.0;
  return run;
}

}  // namespace duskmap
