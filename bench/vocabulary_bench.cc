// Loop closure detection benchmarks (issue 5): quantization of 400
// descriptors, tf-idf likelihood, Bayes update and the whole LCD step
// (quantization + likelihood + filter, lookup-only as in localization) on
// synthetic multi-session maps of 200, 1,200 and 10,000 nodes, for SIFT-like
// float and ORB/BRIEF-like binary descriptors. Also compares the binary
// index kinds, and reports vocabulary memory per word. "float_u8" is the
// float map with its words quantized to 8 bits (the engine's default word
// storage, docs/engine.md). BM_ImportVocabulary opens the six-session
// vocabulary with and without the index a map stores (issue 22).
//
// The maps are realistic in their statistics: each node sees 360 landmarks of
// a sliding window (160 shared with the previous node) plus 40 of 1,000
// generic landmarks, so one session of 200 nodes makes ~41k words (paper:
// ~42k); another session (other lighting) keeps a landmark's appearance with
// probability 0.15, so six sessions make ~210k words (paper: ~231k for 1,207
// nodes). Sessions are linked to session 0 by a loop closure every 20 nodes.
#include <malloc.h>

#include <map>
#include <memory>
#include <numeric>

#include <benchmark/benchmark.h>

#include "slam/core/random.h"
#include "slam/core/timer.h"
#include "slam/retrieval/bayes_filter.h"
#include "slam/retrieval/likelihood.h"
#include "slam/retrieval/loop_closure_detector.h"
#include "slam/vocabulary/synthetic_descriptors.h"

namespace duskmap {
namespace {

constexpr int kNodesPerSession = 200;
constexpr int kQueries = 16;

struct BenchMap {
  std::unique_ptr<LoopClosureDetector> lcd;
  std::unique_ptr<SyntheticDescriptors> gen;
  std::vector<FrameFeatures> queries;  // revisits under a lighting not in the map
  std::vector<std::vector<WordId>> query_words;
  size_t heap_bytes = 0;               // heap growth while building the map
  double build_s = 0.0;
};

FrameFeatures Frame(const SyntheticDescriptors& gen, int session, int position, uint64_t seed) {
  std::vector<int64_t> ids(360);
  std::iota(ids.begin(), ids.end(), 200 * static_cast<int64_t>(position));
  Rng rng(seed);
  for (int i = 0; i < 40; ++i) ids.push_back(900000000 + static_cast<int64_t>(rng() % 1000));
  return gen.ToFeatures(gen.Observe(ids, session, 0.15, seed));
}

// Heap in use: small blocks (uordblks) plus mmapped large blocks (hblkhd).
size_t HeapBytes() {
  const struct mallinfo2 info = mallinfo2();
  return info.uordblks + info.hblkhd;
}

std::unique_ptr<BenchMap> BuildMap(DescriptorKind kind, int nodes, IndexKind binary_kind,
                                   DescriptorStorage word_storage) {
  auto map = std::make_unique<BenchMap>();
  SyntheticDescriptorOptions go;
  go.kind = kind;
  go.cols = kind == DescriptorKind::kFloat ? 128 : 32;
  map->gen = std::make_unique<SyntheticDescriptors>(go);
  LoopClosureOptions options;
  options.vocabulary.index.binary_kind = binary_kind;
  options.vocabulary.index.float_storage = word_storage;
  const size_t heap_before = HeapBytes();
  Stopwatch watch;
  map->lcd = std::make_unique<LoopClosureDetector>(options);
  LoopClosureDetector& lcd = *map->lcd;
  const int sessions = std::max(1, nodes / kNodesPerSession);
  NodeId id = 1;
  for (int s = 0; s < sessions; ++s) {
    for (int p = 0; p < kNodesPerSession && id <= nodes; ++p, ++id) {
      lcd.AddMapNode(id, s, Frame(*map->gen, s, p, DeriveSeed(s, p)));
      if (p > 0) lcd.graph().AddLink(id - 1, id, LinkType::kOdometry);
      if (s > 0 && p % 20 == 0) lcd.graph().AddLink(id, p + 1, LinkType::kLoopClosure);
    }
  }
  map->build_s = watch.ElapsedMs() / 1000.0;
  map->heap_bytes = HeapBytes() - heap_before;
  for (int q = 0; q < kQueries; ++q) {
    map->queries.push_back(Frame(*map->gen, 1000 + q, 10 * q + 5, DeriveSeed(77, q)));
    map->query_words.push_back(
        lcd.vocabulary().Quantize(map->queries.back().descriptors, kind).DistinctWords());
  }
  return map;
}

// One map alive at a time (the 10,000-node float map alone holds ~1.5 GB).
BenchMap& GetMap(DescriptorKind kind, int nodes, IndexKind binary_kind = IndexKind::kBitKdTree,
                 DescriptorStorage word_storage = DescriptorStorage::kFloat32) {
  static std::tuple<DescriptorKind, int, IndexKind, DescriptorStorage> key{
      DescriptorKind::kFloat, -1, binary_kind, word_storage};
  static std::unique_ptr<BenchMap> map;
  const auto wanted = std::make_tuple(kind, nodes, binary_kind, word_storage);
  if (!map || key != wanted) {
    map.reset();
    map = BuildMap(kind, nodes, binary_kind, word_storage);
    key = wanted;
  }
  return *map;
}

void MapCounters(benchmark::State& state, const BenchMap& map) {
  const Vocabulary& v = map.lcd->vocabulary();
  state.counters["nodes"] = static_cast<double>(v.num_nodes());
  state.counters["words"] = static_cast<double>(v.num_words());
  state.counters["bytes_per_word"] = static_cast<double>(v.MemoryBytes()) / v.num_words();
  state.counters["heap_bytes_per_word"] = static_cast<double>(map.heap_bytes) / v.num_words();
  state.counters["build_s"] = map.build_s;
}

// range(0): 0 float (float32 words), 1 binary, 2 float with 8-bit words.
DescriptorKind KindOf(const benchmark::State& state) {
  return state.range(0) == 1 ? DescriptorKind::kBinary : DescriptorKind::kFloat;
}

DescriptorStorage WordStorageOf(const benchmark::State& state) {
  return state.range(0) == 2 ? DescriptorStorage::kUint8 : DescriptorStorage::kFloat32;
}

BenchMap& MapOf(const benchmark::State& state) {
  return GetMap(KindOf(state), static_cast<int>(state.range(1)), IndexKind::kBitKdTree,
                WordStorageOf(state));
}

void BM_Quantize400(benchmark::State& state) {
  BenchMap& map = MapOf(state);
  int q = 0;
  double matched = 0;
  for (auto _ : state) {
    const FrameFeatures& f = map.queries[q++ % kQueries];
    const NodeQuantization r = map.lcd->vocabulary().Quantize(f.descriptors, f.kind);
    matched += r.matched_words;
    benchmark::DoNotOptimize(r.words.data());
  }
  MapCounters(state, map);
  state.counters["matched_fraction"] = matched / (400.0 * state.iterations());
}

void BM_Likelihood(benchmark::State& state) {
  BenchMap& map = MapOf(state);
  const LoopClosureDetector& lcd = *map.lcd;
  int q = 0;
  for (auto _ : state) {
    const Likelihood l = ComputeLikelihood(
        lcd.vocabulary().inverted_index(), map.query_words[q++ % kQueries], false,
        [&lcd](NodeId n) { return lcd.IsCandidate(n); },
        static_cast<int>(lcd.filter().num_places()));
    benchmark::DoNotOptimize(l.virtual_place);
  }
  MapCounters(state, map);
}

void BM_BayesUpdate(benchmark::State& state) {
  BenchMap& map = MapOf(state);
  const LoopClosureDetector& lcd = *map.lcd;
  BayesFilter filter(BayesFilterOptions(), &lcd.graph());
  for (NodeId n : lcd.filter().Places()) filter.AddPlace(n);
  std::vector<Likelihood> likelihoods;
  for (int q = 0; q < kQueries; ++q) {
    likelihoods.push_back(ComputeLikelihood(
        lcd.vocabulary().inverted_index(), map.query_words[q], false,
        [&lcd](NodeId n) { return lcd.IsCandidate(n); },
        static_cast<int>(lcd.filter().num_places())));
  }
  filter.Update(likelihoods[0]);  // builds every transition column once
  int q = 0;
  for (auto _ : state) {
    filter.Update(likelihoods[q++ % kQueries]);
    benchmark::DoNotOptimize(filter.VirtualPosterior());
  }
  MapCounters(state, map);
  state.counters["transition_MB"] = filter.TransitionBytes() / 1e6;
  state.counters["dense_reference_MB"] = 4.0 * filter.num_places() * filter.num_places() / 1e6;
}

// The whole LCD step of a localization frame.
void BM_Lcd(benchmark::State& state) {
  BenchMap& map = MapOf(state);
  map.lcd->Localize(map.queries[0]);  // transition columns built once
  int q = 0;
  for (auto _ : state) {
    const LcdResult r = map.lcd->Localize(map.queries[q++ % kQueries]);
    benchmark::DoNotOptimize(r.score);
  }
  MapCounters(state, map);
}

// Binary index kinds on the six-session map: speed and matches found.
void BM_BinaryIndexQuantize400(benchmark::State& state) {
  const IndexKind kind = static_cast<IndexKind>(state.range(0));
  state.SetLabel(IndexKindName(kind));
  BenchMap& map = GetMap(DescriptorKind::kBinary, 1200, kind);
  int q = 0;
  double matched = 0;
  for (auto _ : state) {
    const FrameFeatures& f = map.queries[q++ % kQueries];
    const NodeQuantization r = map.lcd->vocabulary().Quantize(f.descriptors, f.kind);
    matched += r.matched_words;
    benchmark::DoNotOptimize(r.words.data());
  }
  MapCounters(state, map);
  state.counters["matched_fraction"] = matched / (400.0 * state.iterations());
}

// Opening a map's vocabulary (Vocabulary::Import) on the six-session map,
// range(1) = 1: with the index the map stores (restored), 0: without
// (built, as every load did before maps stored it).
void BM_ImportVocabulary(benchmark::State& state) {
  BenchMap& map = GetMap(KindOf(state), 1200, IndexKind::kBitKdTree, WordStorageOf(state));
  const VocabularyOptions& options = map.lcd->vocabulary().options();
  VocabularySnapshot snapshot = map.lcd->vocabulary().Export();
  if (state.range(1) == 1) {
    Vocabulary built(options);
    built.Import(snapshot);
    snapshot.index_state = built.SaveIndexState();
  }
  bool restored = false;
  for (auto _ : state) {
    Vocabulary v(options);
    v.Import(snapshot);
    restored = v.index_restore().restored;
    benchmark::DoNotOptimize(v.num_words());
  }
  state.SetLabel(restored ? "restored" : "built");
  state.counters["words"] = static_cast<double>(snapshot.word_ids.size());
  state.counters["index_MB"] = snapshot.index_state.size() / 1e6;
}

// Registered per map so that each map is built once.
void RegisterAll() {
  for (int kind : {0, 1, 2}) {
    for (int nodes : {200, 1200, 10000}) {
      const char* name = kind == 0 ? "/float/" : kind == 1 ? "/binary/" : "/float_u8/";
      const std::string suffix = name + std::to_string(nodes);
      benchmark::RegisterBenchmark(("BM_Quantize400" + suffix).c_str(), BM_Quantize400)
          ->Args({kind, nodes})->Unit(benchmark::kMillisecond)->MinTime(0.5);
      benchmark::RegisterBenchmark(("BM_Likelihood" + suffix).c_str(), BM_Likelihood)
          ->Args({kind, nodes})->Unit(benchmark::kMillisecond)->MinTime(0.5);
      benchmark::RegisterBenchmark(("BM_BayesUpdate" + suffix).c_str(), BM_BayesUpdate)
          ->Args({kind, nodes})->Unit(benchmark::kMillisecond)->MinTime(0.5);
      benchmark::RegisterBenchmark(("BM_Lcd" + suffix).c_str(), BM_Lcd)
          ->Args({kind, nodes})->Unit(benchmark::kMillisecond)->MinTime(0.5);
    }
  }
  for (int kind : {1, 2}) {
    const std::string name = kind == 1 ? "binary" : "float_u8";
    for (int stored : {0, 1}) {
      benchmark::RegisterBenchmark(("BM_ImportVocabulary/" + name + "/1200").c_str(),
                                   BM_ImportVocabulary)
          ->Args({kind, stored})->Unit(benchmark::kMillisecond)->Iterations(3);
    }
  }
  for (IndexKind k : {IndexKind::kBitKdTree, IndexKind::kLsh, IndexKind::kHierarchical,
                      IndexKind::kLinear}) {
    benchmark::RegisterBenchmark("BM_BinaryIndexQuantize400/1200", BM_BinaryIndexQuantize400)
        ->Arg(static_cast<int>(k))->Unit(benchmark::kMillisecond)->MinTime(0.5);
  }
}

}  // namespace
}  // namespace duskmap

int main(int argc, char** argv) {
  duskmap::RegisterAll();
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
