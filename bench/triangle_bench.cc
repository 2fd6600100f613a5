// Throughput of the furniture meshes' building blocks: rasterizing small
// triangles (a tessellated sphere of about 50,000, half of them back faces)
// at 640x480, building a BVH over them, and tracing shadow and nearest-hit
// rays through it. The time_per_* counters are seconds per triangle or ray
// (printed with an SI prefix, e.g. 87.6ns).
#include <array>
#include <cmath>
#include <random>
#include <vector>

#include <benchmark/benchmark.h>

#include "slam/synthetic/raster/triangle_bvh.h"
#include "slam/synthetic/raster/triangle_raster.h"

namespace duskmap {
namespace {

constexpr double kPi = 3.14159265358979323846;

// A UV sphere: `stacks` x `slices` quads as two triangles each (one at the
// poles), counter-clockwise seen from outside.
std::vector<std::array<Eigen::Vector3d, 3>> Sphere(const Eigen::Vector3d& centre, double radius, int stacks,
                                                   int slices) {
  auto point = [&](int i, int j) {
    const double theta = kPi * i / stacks, phi = 2.0 * kPi * j / slices;
    return Eigen::Vector3d(centre + radius * Eigen::Vector3d(std::sin(theta) * std::cos(phi),
                                                              std::sin(theta) * std::sin(phi), std::cos(theta)));
  };
  std::vector<std::array<Eigen::Vector3d, 3>> triangles;
  for (int i = 0; i < stacks; ++i) {
    for (int j = 0; j < slices; ++j) {
      const Eigen::Vector3d p00 = point(i, j), p01 = point(i, j + 1), p10 = point(i + 1, j),
                            p11 = point(i + 1, j + 1);
      if (i > 0) triangles.push_back({p00, p10, p01});
      if (i + 1 < stacks) triangles.push_back({p01, p10, p11});
    }
  }
  return triangles;
}

// 125 x 200 quads: 49,600 triangles.
const std::vector<std::array<Eigen::Vector3d, 3>>& SphereInCamera() {
  static const std::vector<std::array<Eigen::Vector3d, 3>> sphere =
      Sphere(Eigen::Vector3d(0.0, 0.0, 3.0), 1.0, 125, 200);
  return sphere;
}

PinholeCamera Vga() {
  PinholeCamera c;
  c.width = 640;
  c.height = 480;
  c.fx = c.fy = 525.0;
  c.cx = 319.5;
  c.cy = 239.5;
  return c;
}

// Argument: 1 = back faces culled (the default), 0 = both sides drawn.
void BM_RasterizeSphere640x480(benchmark::State& state) {
  const PinholeCamera camera = Vga();
  const auto& triangles = SphereInCamera();
  TriangleRasterOptions options;
  options.cull_mode = state.range(0) ? CullMode::kBack : CullMode::kNone;
  TriangleRasterTarget target;
  int64_t pixels = 0;
  for (auto _ : state) {
    target.Reset(camera);
    for (size_t i = 0; i < triangles.size(); ++i) {
      pixels += RasterizeTriangle(camera, options, triangles[i], static_cast<int>(i), &target);
    }
    benchmark::DoNotOptimize(target.ids.data);
  }
  state.counters["triangles"] = static_cast<double>(triangles.size());
  state.counters["px_written"] = benchmark::Counter(static_cast<double>(pixels), benchmark::Counter::kAvgIterations);
  state.counters["time_per_triangle"] = benchmark::Counter(
      static_cast<double>(triangles.size()),
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(triangles.size()));
}
BENCHMARK(BM_RasterizeSphere640x480)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond);

std::vector<WorldTriangle> SphereInWorld() {
  std::vector<WorldTriangle> triangles;
  for (const auto& t : Sphere(Eigen::Vector3d(0.0, 0.0, 1.5), 0.5, 125, 200)) {
    triangles.push_back({t[0].cast<float>(), t[1].cast<float>(), t[2].cast<float>()});
  }
  return triangles;
}

const TriangleBvh& SphereBvh() {
  static const TriangleBvh bvh(SphereInWorld());
  return bvh;
}

void BM_BuildBvh(benchmark::State& state) {
  const std::vector<WorldTriangle> triangles = SphereInWorld();
  for (auto _ : state) {
    TriangleBvh bvh(triangles);
    benchmark::DoNotOptimize(bvh.num_nodes());
  }
  state.counters["triangles"] = static_cast<double>(triangles.size());
  state.counters["time_per_triangle"] = benchmark::Counter(
      static_cast<double>(triangles.size()),
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_BuildBvh)->Unit(benchmark::kMillisecond);

// 1e5 shadow rays from points on the floor (4 m x 4 m around the sphere's
// foot) towards a lamp 3 m up: some pass the sphere, some are stopped by it.
struct ShadowRays {
  std::vector<Eigen::Vector3d> origin, direction;
  std::vector<double> distance;
};

const ShadowRays& FloorToLamp() {
  static const ShadowRays rays = [] {
    ShadowRays r;
    std::mt19937_64 rng(17);
    std::uniform_real_distribution<double> floor(-2.0, 2.0);
    const Eigen::Vector3d lamp(0.3, -0.2, 3.0);
    for (int i = 0; i < 100000; ++i) {
      const Eigen::Vector3d o(floor(rng), floor(rng), 0.0);
      r.origin.push_back(o);
      r.direction.push_back((lamp - o).normalized());
      r.distance.push_back((lamp - o).norm());
    }
    return r;
  }();
  return rays;
}

void BM_ShadowRays(benchmark::State& state) {
  const TriangleBvh& bvh = SphereBvh();
  const ShadowRays& rays = FloorToLamp();
  int64_t occluded = 0;
  for (auto _ : state) {
    for (size_t i = 0; i < rays.origin.size(); ++i) {
      occluded += bvh.Occluded(rays.origin[i], rays.direction[i], rays.distance[i]);
    }
  }
  const double n = static_cast<double>(rays.origin.size());
  state.counters["rays"] = n;
  state.counters["occluded_fraction"] =
      benchmark::Counter(static_cast<double>(occluded) / n, benchmark::Counter::kAvgIterations);
  state.counters["time_per_ray"] =
      benchmark::Counter(n, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_ShadowRays)->Unit(benchmark::kMillisecond);

// The same rays, nearest hit (what a mirror or a picking ray needs).
void BM_NearestHitRays(benchmark::State& state) {
  const TriangleBvh& bvh = SphereBvh();
  const ShadowRays& rays = FloorToLamp();
  int64_t hits = 0;
  for (auto _ : state) {
    for (size_t i = 0; i < rays.origin.size(); ++i) {
      hits += bvh.Intersect(rays.origin[i], rays.direction[i], rays.distance[i]).has_value();
    }
  }
  const double n = static_cast<double>(rays.origin.size());
  state.counters["hit_fraction"] =
      benchmark::Counter(static_cast<double>(hits) / n, benchmark::Counter::kAvgIterations);
  state.counters["time_per_ray"] =
      benchmark::Counter(n, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_NearestHitRays)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace duskmap

BENCHMARK_MAIN();
