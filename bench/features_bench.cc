// Extraction time of every feature type on one 640x480 frame at
// Vis/MaxFeatures = 1000: the oxford-leuven reference image resized (or a
// deterministic textured image when ../shared is absent). OpenCV runs
// single-threaded so that own and OpenCV-backed extractors compare per core
// (the reference measured single-threaded too). Report medians:
//   build-feat/bench/features_bench --benchmark_repetitions=7
//       --benchmark_report_aggregates_only=true
// SuperPoint is timed when DUSKMAP_SUPERPOINT_ONNX names a model file.
#include <cstdlib>
#include <string>

#include <benchmark/benchmark.h>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "slam/features/feature_extractor.h"

namespace duskmap {
namespace {

cv::Mat TexturedFallback() {
  cv::RNG rng(1);
  cv::Mat image(480, 640, CV_8UC3, cv::Scalar(128, 128, 128));
  for (int i = 0; i < 500; ++i) {
    const cv::Point c(rng.uniform(0, 640), rng.uniform(0, 480));
    cv::circle(image, c, rng.uniform(3, 28), cv::Scalar::all(rng.uniform(0, 256)), cv::FILLED,
               cv::LINE_AA);
  }
  cv::GaussianBlur(image, image, cv::Size(0, 0), 1.0);
  return image;
}

const cv::Mat& Frame() {
  static const cv::Mat kFrame = [] {
    const cv::Mat leuven =
        cv::imread(std::string(DUSKMAP_SHARED_DIR) + "/data/illumination/oxford-leuven/img1.ppm");
    if (leuven.empty()) return TexturedFallback();
    cv::Mat resized;
    cv::resize(leuven, resized, cv::Size(640, 480), 0, 0, cv::INTER_AREA);
    return resized;
  }();
  return kFrame;
}

void BM_Extract(benchmark::State& state, const std::string& type) {
  cv::setNumThreads(1);
  FeatureOptions options;
  options.type = type;
  if (type == "superpoint") options.superpoint.model_path = std::getenv("DUSKMAP_SUPERPOINT_ONNX");
  const auto extractor = CreateFeatureExtractor(options);
  size_t keypoints = 0;
  for (auto _ : state) {
    const FrameFeatures f = extractor->Extract(Frame());
    keypoints = f.size();
    benchmark::DoNotOptimize(f.descriptors.data);
  }
  state.counters["keypoints"] = static_cast<double>(keypoints);
}

const bool kRegistered = [] {
  for (const std::string& type : FeatureTypeNames()) {
    if (type == "superpoint" && std::getenv("DUSKMAP_SUPERPOINT_ONNX") == nullptr) continue;
    benchmark::RegisterBenchmark(("Extract/" + type).c_str(), BM_Extract, type)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
  }
  return true;
}();

}  // namespace
}  // namespace duskmap

BENCHMARK_MAIN();
