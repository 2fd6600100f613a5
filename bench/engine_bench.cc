// Engine timings on synthetic sessions, features already extracted (the
// issue's targets): the localization step (LCD + TE) on a six-session map,
// and mapping one session; and the per-node memory of a map by feature type
// and descriptor storage (BM_NodeMemory).
//
// Data: $DUSKMAP_BENCH_DATASET when set (a synthetic dataset with mapping
// sessions 1-6 and localization session A), otherwise a dataset generated
// once into <system temp>/duskmap_engine_bench_<frames> (/tmp/...) with the
// default 640x480 camera and the first $DUSKMAP_BENCH_FRAMES (default 60)
// frames per session. That folder is kept across runs on purpose
// (bench_temp_dir.h's BenchCachePath, not the per-process scratch folder):
// later runs skip the generation, and the `duskmap map` measurements of
// docs/engine.md use it.
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#include <map>

#include "bench/bench_temp_dir.h"
#include "slam/core/timer.h"
#include "slam/engine/localizer.h"
#include "slam/engine/mapper.h"
#include "slam/engine/session_runs.h"
#include "slam/features/feature_factory.h"
#include "slam/io/synthetic_dataset.h"
#include "slam/map/map_memory.h"
#include "slam/synthetic/generator.h"

namespace duskmap {
namespace {

struct CachedFrame {
  RgbdFrame frame;
  FrameFeatures features;
};

struct BenchData {
  EngineOptions options;
  std::map<std::string, std::vector<CachedFrame>> sessions;
  std::unique_ptr<Map> six_session_map;
};

int BenchFrames() {
  const char* env = std::getenv("DUSKMAP_BENCH_FRAMES");
  return env ? std::atoi(env) : 60;
}

std::string DatasetPath() {
  if (const char* env = std::getenv("DUSKMAP_BENCH_DATASET")) return env;
  const std::string path = bench::BenchCachePath("duskmap_engine_bench_" + std::to_string(BenchFrames()));
  if (!std::filesystem::exists(path)) {
    GeneratorConfig config;  // the box apartment without motion blur
    ApplyGeneratorModel("boxes-2026-12-02", &config);
    config.camera.exposure.motion_blur_scale = 0.0;
    config.max_frames = BenchFrames();
    config.sessions = {{"1", "16:46", "mapping"}, {"2", "17:27", "mapping"},
                       {"3", "17:54", "mapping"}, {"4", "18:27", "mapping"},
                       {"5", "18:56", "mapping"}, {"6", "19:35", "mapping"},
                       {"A", "16:51", "localization"}};
    GenerateOptions options;
    options.output_path = path;
    GenerateDataset(config, options);
  }
  return path;
}

// Reads every frame of the sessions and extracts its features once.
BenchData& Data() {
  static BenchData* data = [] {
    auto* d = new BenchData();
    const auto dataset = OpenSyntheticDataset(DatasetPath());
    const auto extractor = CreateFeatureExtractor(d->options.features);
    for (const std::string name : {"1", "2", "3", "4", "5", "6", "A"}) {
      auto reader = dataset->OpenSession(name);
      while (auto frame = reader->Next()) {
        FrameFeatures features = extractor->Extract(frame->bgr, frame->depth_m, &frame->camera);
        frame->bgr.release();  // not needed any more
        frame->depth_m.release();
        d->sessions[name].push_back({std::move(*frame), std::move(features)});
      }
    }
    Mapper mapper(d->options);
    for (const std::string name : {"1", "2", "3", "4", "5", "6"}) {
      mapper.StartSession(name, std::nullopt);
      for (const CachedFrame& f : d->sessions[name]) mapper.ProcessFrame(f.frame, f.features);
    }
    d->six_session_map = std::make_unique<Map>(mapper.Finish());
    return d;
  }();
  return *data;
}

void BM_LocalizationStep(benchmark::State& state) {
  BenchData& data = Data();
  std::vector<double> steps_ms;
  int relocalized = 0, frames = 0;
  for (auto _ : state) {
    state.PauseTiming();
    Localizer localizer(*data.six_session_map, data.options);
    state.ResumeTiming();
    double session_ms = 0.0;
    for (const CachedFrame& f : data.sessions["A"]) {
      const LocalizationRecord record = localizer.ProcessFrame(f.frame, f.features);
      const double step_ms = record.timings.lcd_ms + record.timings.proximity_ms +
                             record.timings.registration_ms;
      steps_ms.push_back(step_ms);
      session_ms += step_ms;
      relocalized += record.relocalized;
      ++frames;
    }
    state.SetIterationTime(session_ms / 1000.0);
  }
  state.counters["median_step_ms"] = SummarizeTimes(steps_ms).median_ms;
  state.counters["mean_step_ms"] = SummarizeTimes(steps_ms).mean_ms;
  state.counters["relocalized_pct"] = frames ? 100.0 * relocalized / frames : 0.0;
  state.counters["map_nodes"] = static_cast<double>(data.six_session_map->nodes().size());
  state.counters["frames"] = static_cast<double>(data.sessions["A"].size());
}
BENCHMARK(BM_LocalizationStep)->UseManualTime()->Iterations(3)->Unit(benchmark::kMillisecond);

void BM_MapSession(benchmark::State& state) {
  BenchData& data = Data();
  const auto& frames = data.sessions["1"];
  double total_ms = 0.0;
  int sessions = 0;
  for (auto _ : state) {
    Stopwatch watch;
    Mapper mapper(data.options);
    mapper.StartSession("1", std::nullopt);
    for (const CachedFrame& f : frames) mapper.ProcessFrame(f.frame, f.features);
    benchmark::DoNotOptimize(mapper.Finish());
    total_ms += watch.ElapsedMs();
    ++sessions;
  }
  state.counters["frames"] = static_cast<double>(frames.size());
  state.counters["ms_per_frame"] = total_ms / sessions / frames.size();
}
BENCHMARK(BM_MapSession)->Iterations(2)->Unit(benchmark::kMillisecond);

// Per-node memory needed for localization, by feature type and descriptor
// storage (float32 as extracted, uint8 quantized), with the re-localization
// rate it gives: map built from session 1 then 2 (the first
// $DUSKMAP_BENCH_MEMORY_FRAMES frames each, default 30), session A localized.
// Counters are bytes per node (kB = 1000 B); the paper's SURF map
// 1+2+3+4+5+6 needs (583 - 90) MB / 1207 nodes = 408 kB per node.
const std::vector<std::string> kMemoryFeatures = {"surf",  "sift", "orb",  "brief",
                                                  "brisk", "kaze", "daisy"};

int MemoryFrames() {
  const char* env = std::getenv("DUSKMAP_BENCH_MEMORY_FRAMES");
  return env ? std::atoi(env) : 30;
}

// Features of sessions 1, 2 and A for one extractor, extracted once.
const std::map<std::string, std::vector<CachedFrame>>& FeaturesFor(const std::string& type) {
  static std::map<std::string, std::map<std::string, std::vector<CachedFrame>>> cache;
  auto it = cache.find(type);
  if (it != cache.end()) return it->second;
  EngineOptions options;
  options.features.type = type;
  const auto dataset = OpenSyntheticDataset(DatasetPath());
  const auto extractor = CreateFeatureExtractor(options.features);
  std::map<std::string, std::vector<CachedFrame>> sessions;
  for (const std::string name : {"1", "2", "A"}) {
    auto reader = dataset->OpenSession(name);
    for (int i = 0; i < MemoryFrames(); ++i) {
      auto frame = reader->Next();
      if (!frame) break;
      FrameFeatures features = extractor->Extract(frame->bgr, frame->depth_m, &frame->camera);
      frame->bgr.release();
      frame->depth_m.release();
      sessions[name].push_back({std::move(*frame), std::move(features)});
    }
  }
  return cache.emplace(type, std::move(sessions)).first->second;
}

void BM_NodeMemory(benchmark::State& state) {
  const std::string type = kMemoryFeatures.at(static_cast<size_t>(state.range(0)));
  const auto storage = state.range(1) ? DescriptorStorage::kUint8 : DescriptorStorage::kFloat32;
  state.SetLabel(type + "/" + DescriptorStorageName(storage));
  const auto& sessions = FeaturesFor(type);
  EngineOptions options;
  options.features.type = type;
  options.mapping.descriptor_storage = storage;
  MapMemory memory;
  int relocalized = 0, frames = 0;
  for (auto _ : state) {
    Mapper mapper(options);
    for (const std::string name : {"1", "2"}) {
      mapper.StartSession(name, std::nullopt);
      for (const CachedFrame& f : sessions.at(name)) mapper.ProcessFrame(f.frame, f.features);
    }
    const Map map = mapper.Finish();
    Localizer localizer(map, options);
    relocalized = frames = 0;
    for (const CachedFrame& f : sessions.at("A")) {
      relocalized += localizer.ProcessFrame(f.frame, f.features).relocalized;
      ++frames;
    }
    // As LocalizeSession counts it: the map's nodes and graph, the live
    // vocabulary and the Bayes filter.
    const LoopClosureDetector& lcd = localizer.loop_closure();
    memory = ComputeMapMemory(
        map, lcd.filter().TransitionBytes() + lcd.filter().num_places() * sizeof(double));
    memory.words_index_bytes = lcd.vocabulary().MemoryBytes();
  }
  const double nodes = static_cast<double>(memory.num_nodes);
  state.counters["nodes"] = nodes;
  state.counters["node_bytes"] = memory.bytes_per_node();
  state.counters["descriptor_bytes"] = memory.descriptors_bytes / nodes;
  state.counters["keypoint_point_bytes"] = memory.keypoints_points_bytes / nodes;
  state.counters["words_index_bytes"] = memory.words_index_bytes / nodes;
  state.counters["graph_filter_bytes"] = (memory.graph_bytes + memory.filter_bytes) / nodes;
  state.counters["relocalized_pct"] = frames ? 100.0 * relocalized / frames : 0.0;
}
BENCHMARK(BM_NodeMemory)
    ->ArgsProduct({benchmark::CreateDenseRange(0, 6, 1), {0, 1}})
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace duskmap

BENCHMARK_MAIN();
