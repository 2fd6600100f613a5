// Rendering throughput of the synthetic apartment at 640x480 once a session's
// lighting is prepared (target: >= 20 frames/s on one core), the cost of the
// lighting preparation, the frame path (render + camera + depth) and the
// whole per-frame generation cost including the PNG files the dataset holds.
#include <filesystem>
#include <memory>
#include <string>

#include <benchmark/benchmark.h>

#include "bench/bench_temp_dir.h"
#include "slam/io/tum_writer.h"
#include "slam/synthetic/assets/furniture_catalog.h"
#include "slam/synthetic/generator_config.h"
#include "slam/synthetic/scene/apartment.h"
#include "slam/synthetic/sensor/route.h"
#include "slam/synthetic/session_simulator.h"

namespace duskmap {
namespace {

// The box apartment (boxes-2026-12-02).
GeneratorConfig BoxesConfig() {
  GeneratorConfig config;
  ApplyGeneratorModel("boxes-2026-12-02", &config);
  return config;
}

struct Fixture {
  GeneratorConfig config = BoxesConfig();
  Scene scene = BuildApartment(ApartmentOptions());
  std::vector<TimedPose> route = GenerateRoute(RouteOptions(), ApartmentPatrolRoute(), 1);
};

Fixture& Shared() {
  static Fixture fixture;
  return fixture;
}

// The default apartment, furnished with catalog models
// (configs/sunset_apartment.json); null when the catalog is not installed.
const Fixture* Furnished() {
  static const std::unique_ptr<Fixture> fixture = []() -> std::unique_ptr<Fixture> {
    if (!std::filesystem::exists(DefaultFurnitureCatalogPath())) return nullptr;
    auto f = std::make_unique<Fixture>();
    f->config = ReadGeneratorConfig(std::string(DUSKMAP_SOURCE_DIR) + "/configs/sunset_apartment.json");
    f->scene = BuildApartment(f->config.scene);
    return f;
  }();
  return fixture.get();
}

// Argument: 0 = the box-furniture apartment (configs/sunset_apartment_boxes.json's
// scene), 1 = the default, furnished with catalog meshes.
void BM_RenderFrame640x480(benchmark::State& state) {
  const Fixture* furnished = state.range(0) ? Furnished() : nullptr;
  if (state.range(0) && furnished == nullptr) {
    state.SkipWithError("sweethome3d-furniture not installed: run scripts/setup.sh");
    return;
  }
  const Fixture& f = furnished ? *furnished : Shared();
  SessionSimulator simulator(f.config, f.scene, 17.0, 1);
  RenderedView view;
  size_t k = 0;
  for (auto _ : state) {
    simulator.renderer().Render(simulator.radiance(), f.route[k++ % f.route.size()].world_from_camera, &view);
    benchmark::DoNotOptimize(view.radiance.data);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_RenderFrame640x480)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

void BM_CaptureFrame640x480(benchmark::State& state) {
  Fixture& f = Shared();
  SessionSimulator simulator(f.config, f.scene, 19.7, 2);
  size_t k = 0;
  for (auto _ : state) {
    RgbdFrame frame = simulator.Capture(f.route[k++ % f.route.size()].world_from_camera);
    benchmark::DoNotOptimize(frame.bgr.data);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_CaptureFrame640x480)->Unit(benchmark::kMillisecond);

// Capture plus writing the colour and depth PNGs (what `duskmap generate`
// does per frame), into a scratch folder of this process (bench_temp_dir.h).
void BM_CaptureAndWriteFrame640x480(benchmark::State& state) {
  Fixture& f = Shared();
  SessionSimulator simulator(f.config, f.scene, 19.7, 2);
  const std::string folder = bench::BenchTempDir("capture_and_write");
  TumCalibration calibration;
  calibration.camera = f.config.camera.Intrinsics();
  calibration.depth_scale = 1000.0;
  {
    TumSessionWriter writer(folder, calibration);
    size_t k = 0;
    for (auto _ : state) {
      RgbdFrame frame = simulator.Capture(f.route[k % f.route.size()].world_from_camera);
      frame.timestamp_s = static_cast<double>(k++);
      writer.Write(frame);
    }
  }
  std::filesystem::remove_all(folder);
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_CaptureAndWriteFrame640x480)->Unit(benchmark::kMillisecond);

// Argument: 1 = the box scene (materials with relief), 0 = every surface
// flat, 2 = furnished with catalog meshes (their vertices lit too) and the
// default config's lighting with the windows' view open (the sky in every
// direction), 3 = the same with the view obstructed (facades and ground
// below the horizon: six polygons per window instead of one).
void BM_PrepareLighting(benchmark::State& state) {
  Fixture& f = Shared();
  static const Scene flat = [] {
    ApartmentOptions options;
    options.relief_scale = 0.0;
    return BuildApartment(options);
  }();
  const bool furnished = state.range(0) >= 2;
  if (furnished && Furnished() == nullptr) {
    state.SkipWithError("sweethome3d-furniture not installed: run scripts/setup.sh");
    return;
  }
  const Scene& scene = furnished ? Furnished()->scene : state.range(0) ? f.scene : flat;
  LightingOptions options = furnished ? Furnished()->config.lighting : f.config.lighting;
  if (furnished) options.window_view_obstructed = state.range(0) == 3;
  for (auto _ : state) {
    const SessionLighting lighting = ComputeSessionLighting(options, scene, 16.8);
    SessionRadiance radiance = PrepareSessionRadiance(scene, lighting, options);
    benchmark::DoNotOptimize(radiance.quads.data());
  }
}
BENCHMARK(BM_PrepareLighting)->Arg(1)->Arg(0)->Arg(2)->Arg(3)->Unit(benchmark::kMillisecond)->Iterations(2);

}  // namespace
}  // namespace duskmap

BENCHMARK_MAIN();
