#include "slam/experiment/engine_executor.h"

#include <fstream>
#include <numeric>
#include <utility>
#include <vector>

#include "slam/core/check.h"
#include "slam/core/system_error.h"
#include "slam/core/timer.h"
#include "slam/engine/record_io.h"
#include "slam/engine/session_runs.h"
#include "slam/eval/trajectory_error.h"
#include "slam/experiment/feature_cache.h"
#include "slam/experiment/job_results_json.h"
#include "slam/features/feature_factory.h"
#include "slam/features/feature_registry.h"
#include "slam/map/map_store.h"

namespace duskmap {
namespace fs = std::filesystem;
namespace {

void WriteJsonRows(const fs::path& path, const std::vector<nlohmann::json>& rows) {
  std::ofstream out(path);
  SLAM_THROW_IF_NOT(InputError, out.good()) << path.string() << ": cannot write";
  WriteJsonLines(out, rows);
  SLAM_THROW_IF_NOT(InputError, out.good()) << path.string() << ": write failed: " << LastSystemError();
}

// ATE of the nodes of the session group holding the map's first session (the
// map frame) against ground truth, and the graph (aligned to the truth) for
// the top-view figure. ate_mm stays < 0 without ground truth.
double WriteGraphAndAte(const Map& map, const fs::path& graph_file) {
  std::vector<SessionId> group;
  for (const auto& g : map.ConnectedSessionGroups()) {
    for (SessionId s : g) {
      if (s == 0) group = g;
    }
  }
  std::vector<const MapNode*> nodes;
  std::vector<Rigid3d> estimated, truth;
  for (const auto& [id, node] : map.nodes()) {
    nodes.push_back(&node);
    const bool in_group = std::find(group.begin(), group.end(), node.session) != group.end();
    if (in_group && node.truth_from_camera) {
      estimated.push_back(node.map_from_camera());
      truth.push_back(*node.truth_from_camera);
    }
  }
  std::optional<AteResult> ate;
  if (estimated.size() >= 3) ate = ComputeAte(estimated, truth);
  std::ofstream out(graph_file);
  SLAM_THROW_IF_NOT(InputError, out.good()) << graph_file.string() << ": cannot write";
  out << "node,session,connected,x,y,truth_x,truth_y\n";
  for (const MapNode* node : nodes) {
    Eigen::Vector3d p = node->map_from_camera().translation;
    if (ate) p = ate->alignment.Apply(p);
    const bool in_group = std::find(group.begin(), group.end(), node->session) != group.end();
    out << node->id << "," << map.sessions()[node->session].name << "," << (in_group ? 1 : 0)
        << "," << p.x() << "," << p.y() << ",";
    if (node->truth_from_camera) {
      out << node->truth_from_camera->translation.x() << ","
          << node->truth_from_camera->translation.y();
    } else {
      out << ",";
    }
    out << "\n";
  }
  SLAM_THROW_IF_NOT(InputError, out.good()) << graph_file.string() << ": write failed: " << LastSystemError();
  return ate ? 1000.0 * ate->rmse_m : -1.0;
}

}  // namespace

EngineOptions EngineOptionsForFeature(const EngineOptions& base, const FeatureSetup& setup) {
  EngineOptions options = base;
  setup.ApplyTo(&options.features);  // a declared column's file or model too
  // The column decides the matcher (SP: NNDR, SG: SuperGlue on the same
  // SuperPoint features); the engine config supplies the SuperGlue model.
  options.matcher.type = setup.matcher;
  if (setup.matcher == "superglue") {
    SLAM_THROW_IF_NOT(ConfigError, !options.matcher.superglue.model_path.empty())
        << "feature " << setup.label << " needs matcher.superglue.model_path in the engine config";
  }
  const FeatureType* type = FindFeatureType(setup.extractor);
  if (setup.needs_model && type != nullptr && type->file) {
    SLAM_THROW_IF_NOT(ConfigError, !FeatureFilePath(options.features).empty())
        << "feature " << setup.label << " needs features." << type->file->key
        << " in the engine config";
  }
  options.Check();
  return options;
}

EngineJobExecutor::EngineJobExecutor(const ExperimentOptions& experiment,
                                     const EngineOptions& engine, const DatasetReader& dataset,
                                     fs::path output_dir, SharedFeatureCacheOptions shared_cache)
    : experiment_(experiment),
      engine_(engine),
      dataset_(dataset),
      output_dir_(std::move(output_dir)),
      shared_cache_(std::move(shared_cache)) {}

fs::path EngineJobExecutor::CacheFile(const std::string& extractor,
                                      const std::string& session) const {
  return OutputDir(output_dir_, "extract/" + extractor + "/" + session) / kFeatureCacheFile;
}

double EngineJobExecutor::ExtractionMeanMs(const std::string& extractor,
                                           const std::string& session) const {
  const fs::path dir = OutputDir(output_dir_, "extract/" + extractor + "/" + session);
  return ReadExtractJobSummary(dir).extraction_ms.mean;
}

void EngineJobExecutor::Execute(const Job& job, const fs::path& job_dir) {
  switch (job.kind) {
    case JobKind::kExtract:
      Extract(job, job_dir);
      return;
    case JobKind::kBuildMap:
      BuildMapJob(job, job_dir);
      return;
    case JobKind::kLocalize:
      Localize(job, job_dir);
      return;
  }
}

void EngineJobExecutor::Extract(const Job& job, const fs::path& job_dir) {
  std::unique_ptr<SessionReader> reader;
  {
    std::lock_guard<std::mutex> lock(dataset_mutex_);
    reader = dataset_.OpenSession(job.session);
  }
  EngineOptions options = engine_;
  job.setup.ApplyTo(&options.features);
  options.features.Check();
  std::string shared_key;
  if (shared_cache_.enabled()) {
    shared_key = shared_cache_.KeyOf({job.session, job.extractor, options.features,
                                      experiment_.frame_step, experiment_.max_frames_per_session});
    if (std::optional<ExtractJobSummary> summary =
            shared_cache_.Restore(shared_key, job_dir / kFeatureCacheFile)) {
      summary->shared_cache = "restored " + shared_key;  // timings are the extraction's
      WriteSummary(job_dir, ToJsonObject(*summary));
      return;
    }
  }
  const std::unique_ptr<FeatureExtractor> extractor = CreateFeatureExtractor(options.features);
  FeatureCacheWriter writer(job_dir / kFeatureCacheFile, job.extractor, reader->info());
  std::vector<double> times_ms;
  double features_sum = 0.0;
  int64_t position = 0;
  while (std::optional<RgbdFrame> frame = reader->Next()) {
    const int64_t index = position++;
    if (index % experiment_.frame_step != 0) continue;
    if (experiment_.max_frames_per_session > 0 &&
        writer.num_frames() >= experiment_.max_frames_per_session) {
      break;
    }
    Stopwatch watch;
    const FrameFeatures features = extractor->ExtractFrame(*frame);
    times_ms.push_back(watch.ElapsedMs());
    features_sum += features.size();
    writer.Append(*frame, features);
  }
  writer.Close();
  SLAM_THROW_IF_NOT(InputError, writer.num_frames() > 0)
      << "session " << job.session << ": no frame to extract features from";
  const StageTimingSummary t = SummarizeTimes(times_ms);
  ExtractJobSummary summary;
  summary.extractor = job.extractor;
  summary.session = job.session;
  summary.frames = writer.num_frames();
  summary.mean_features = features_sum / writer.num_frames();
  summary.extraction_ms = {t.median_ms, t.mean_ms, t.max_ms};
  if (shared_cache_.enabled()) {
    shared_cache_.Store(shared_key, job_dir / kFeatureCacheFile, summary);
    summary.shared_cache = "stored " + shared_key;
  }
  WriteSummary(job_dir, ToJsonObject(summary));
}

void EngineJobExecutor::BuildMapJob(const Job& job, const fs::path& job_dir) {
  EngineOptions options = EngineOptionsForFeature(engine_, job.setup);
  options.mapping.reduce_graph = job.map.kind == MapKind::kReduced;
  std::vector<std::unique_ptr<FeatureCacheReader>> readers;
  std::vector<FrameSource*> sources;
  for (const std::string& session : job.map.sessions) {
    readers.push_back(std::make_unique<FeatureCacheReader>(CacheFile(job.extractor, session)));
    sources.push_back(readers.back().get());
  }
  MappingRun run = BuildMap(sources, options);
  SaveMap(run.map, (job_dir / kMapFile).string());

  MapJobSummary summary;
  const Map& map = run.map;
  summary.num_nodes = static_cast<int>(map.nodes().size());
  for (const MapSession& session : map.sessions()) summary.nodes_per_session[session.name] = 0;
  for (const auto& [id, node] : map.nodes()) ++summary.nodes_per_session[map.sessions()[node.session].name];
  for (const auto& [key, link] : map.links()) ++summary.links_per_type[LinkTypeName(link.type)];
  summary.num_connected_components = static_cast<int>(map.ConnectedSessionGroups().size());
  summary.vocabulary_words = static_cast<int>(map.words().ids.size());
  for (const auto& [id, node] : map.nodes()) {
    if (!node.features.empty()) {
      summary.descriptor_bytes_per_feature = node.features.DescriptorBytes();
      break;
    }
  }
  summary.memory_bytes = MemoryBytesByComponent(run.memory);
  summary.ate_mm = WriteGraphAndAte(map, job_dir / kGraphFile);
  double features_sum = 0.0;
  std::vector<nlohmann::json> rows;
  for (const MappingFrameResult& frame : run.frames) {
    features_sum += frame.num_features;
    rows.push_back(MappingResultToJson(frame));
  }
  summary.mean_features = run.frames.empty() ? 0.0 : features_sum / run.frames.size();
  summary.mean_times_ms = MeanStageTimes(run.timings);
  double extraction_ms = 0.0;
  for (const std::string& session : job.map.sessions) {
    extraction_ms += ExtractionMeanMs(job.extractor, session) / job.map.sessions.size();
  }
  summary.mean_times_ms.features = extraction_ms;
  summary.mean_times_ms.total += extraction_ms;
  summary.build_wall_s = run.wall_s;
  summary.index_build_s = run.index_build_s;
  WriteJsonRows(job_dir / kFramesFile, rows);
  WriteSummary(job_dir, ToJsonObject(summary));
}

void EngineJobExecutor::Localize(const Job& job, const fs::path& job_dir) {
  const EngineOptions options = EngineOptionsForFeature(engine_, job.setup);
  const std::string map_file =
      (OutputDir(output_dir_, "map/" + job.feature + "/" + job.map.label) / kMapFile).string();
  // The words apart: the localizer imports its copy of them (the rows are
  // shared, not copied) into its index.
  const SharedMap shared = maps_.Get(map_file, options.LocalizationMapLoad());
  const MapAndWords& loaded = *shared.loaded;
  FeatureCacheReader source(CacheFile(job.extractor, job.session));
  const LocalizationRun run = LocalizeSession(loaded.map, MapWords(loaded.words), source, options);

  LocalizationJobSummary summary = SummarizeLocalization(loaded.map, run);
  summary.map_load_s = shared.load_s;
  summary.map_from_cache = shared.from_cache;
  // Features came from the cache: their extraction time is the extract job's.
  summary.mean_times_ms.features = ExtractionMeanMs(job.extractor, job.session);
  summary.mean_times_ms.total += summary.mean_times_ms.features;
  std::vector<nlohmann::json> rows;
  for (const LocalizationRecord& record : run.records) rows.push_back(LocalizationRecordToJson(record));
  WriteJsonRows(job_dir / kFramesFile, rows);
  WriteCorrectedTrajectory((job_dir / kTrajectoryFile).string(), run.records);
  WriteSummary(job_dir, ToJsonObject(summary));
}

}  // namespace duskmap
