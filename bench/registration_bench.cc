// Transformation estimation for one map-node / query pair at
// Vis/MaxFeatures = 1000, per descriptor type, single-threaded.
// The pair: the oxford-leuven reference image (resized to 640x480) seen as a
// tilted plane at ~2 m with depth, and a second, darker leuven image warped by
// the homography of a known camera motion (5 deg, 16 cm); the query has no
// depth. Without ../shared a deterministic texture and a darkened copy are
// used. Report medians:
//   build-reg/bench/registration_bench --benchmark_repetitions=7
//       --benchmark_report_aggregates_only=true
// SURF is duskmap's own (features module) at the paper's Hessian threshold 100.
#include <cmath>
#include <string>

#include <benchmark/benchmark.h>
#include <opencv2/core/utility.hpp>

#include "slam/features/feature_factory.h"
#include "slam/registration/transform_estimation.h"
#include "tests/registration/plane_pair.h"

namespace duskmap {
namespace {

const testing::PlanePair& Pair() {
  static const testing::PlanePair kPair = testing::MakePlanePair(DUSKMAP_SHARED_DIR, 2);
  return kPair;
}

struct ExtractedPair {
  FrameFeatures map_node, query;
};

ExtractedPair Extract(const std::string& type) {
  FeatureOptions options;
  options.type = type;
  options.max_features = 1000;
  const auto extractor = CreateFeatureExtractor(options);
  const testing::PlanePair& pair = Pair();
  return {extractor->Extract(pair.map_image, pair.map_depth_m, &pair.camera),
          extractor->Extract(pair.query_image)};
}

// Pipeline variants measured for docs/registration.md.
enum class Variant { kDefault, kKdTree, kNoBundleAdjustment, kNoRefitNoBundleAdjustment, kOnePass };

void BM_EstimateTransform(benchmark::State& state, const std::string& type, Variant variant) {
  cv::setNumThreads(1);
  const ExtractedPair features = Extract(type);
  const testing::PlanePair& pair = Pair();
  RegistrationOptions options;
  if (variant == Variant::kKdTree) options.matching.search = NndrSearch::kKdTree;
  if (variant == Variant::kNoBundleAdjustment || variant == Variant::kNoRefitNoBundleAdjustment) {
    options.bundle_adjustment.enabled = false;
  }
  if (variant == Variant::kNoRefitNoBundleAdjustment) options.pnp.refine_rounds = 0;
  if (variant == Variant::kOnePass) options.second_pass = false;
  RegistrationResult result;
  for (auto _ : state) {
    result = EstimateTransform(options, features.map_node, pair.camera, features.query,
                               pair.camera);
    benchmark::DoNotOptimize(result.num_inliers);
  }
  state.counters["map_features"] = features.map_node.size();
  state.counters["query_features"] = features.query.size();
  state.counters["accepted"] = result.accepted();
  state.counters["matches1"] = result.matches_first_pass;
  state.counters["matches2"] = result.matches_second_pass;
  state.counters["inliers"] = result.num_inliers;
  state.counters["err_mm"] =
      1000.0 * (result.node_from_query.translation - pair.node_from_query.translation).norm();
  state.counters["err_deg"] =
      RotationAngleRad(result.node_from_query.rotation, pair.node_from_query.rotation) * 180.0 /
      M_PI;
  state.counters["trials"] = result.ransac_trials;
  state.counters["match_ms"] = result.timings.matching_ms;
  state.counters["pnp_ms"] = result.timings.pnp_ms;
  state.counters["pass2_ms"] = result.timings.second_pass_ms;
  state.counters["ba_ms"] = result.timings.bundle_adjustment_ms;
}

BENCHMARK_CAPTURE(BM_EstimateTransform, sift, std::string("sift"), Variant::kDefault)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_EstimateTransform, orb, std::string("orb"), Variant::kDefault)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_EstimateTransform, surf, std::string("surf"), Variant::kDefault)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_EstimateTransform, sift_kdtree, std::string("sift"), Variant::kKdTree)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_EstimateTransform, sift_no_ba, std::string("sift"),
                  Variant::kNoBundleAdjustment)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_EstimateTransform, sift_no_refit_no_ba, std::string("sift"),
                  Variant::kNoRefitNoBundleAdjustment)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_EstimateTransform, sift_one_pass, std::string("sift"), Variant::kOnePass)
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace duskmap

BENCHMARK_MAIN();
