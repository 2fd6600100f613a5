// Extraction time of every feature type on one 640x480 frame at
// Vis/MaxFeatures = 1000: the oxford-leuven reference image resized (or a
// deterministic textured image when ../shared is absent). OpenCV runs
// single-threaded so that own and OpenCV-backed extractors compare per core
// (the reference measured single-threaded too). Extract/kaze/single_pass is
// KAZE described in its detection pass (kaze.single_pass). Report medians:
//   build-feat/bench/features_bench --benchmark_repetitions=7
//       --benchmark_report_aggregates_only=true
// SuperPoint is timed when DUSKMAP_SUPERPOINT_ONNX names a model file, the
// generic onnx type when DUSKMAP_ONNX_FEATURES names a JSON file of
// features.onnx options (its model and contract).
// Describe/sift and Describe/dusknet: the descriptor time alone on the same
// 1,000 SIFT keypoints of the frame (detected once, outside the timing; one
// thread): cv::SIFT's compute (which builds its own scale space) beside the
// dusknet type's patches and network (its embedded model, or the file that
// DUSKMAP_DUSKNET_ONNX names, e.g. a training candidate).
// ImportH5: the h5 type reading one frame's features (1000 keypoints with
// 128-D float32 or 32-byte binary descriptors and scores, hloc's layout) from
// a 100-frame file, with 3D points from a 640x480 depth image.
// SuperGlue matching of 1000 x 1000 keypoints (random 256-D descriptors,
// 640x480 images) is timed when DUSKMAP_SUPERGLUE_ONNX names a model file,
// e.g. one written by scripts/make_test_superglue_onnx.py (same size and
// graph as the official weights); it runs with OpenCV's default threads
// (CPU time is the whole process's).
#include <cstdlib>
#include <filesystem>
#include <string>

#include <benchmark/benchmark.h>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "bench/bench_temp_dir.h"
#include "slam/features/feature_factory.h"
#include "slam/features/feature_options_json.h"
#include "slam/features/h5_feature_file.h"
#include "slam/features/onnx_patch_extractor.h"
#include "slam/features/opencv_extractors.h"
#include "slam/features/superglue.h"

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

// `kaze_single_pass`: KAZE described in its detection pass (kaze.single_pass).
void BM_Extract(benchmark::State& state, const std::string& type, bool kaze_single_pass) {
  cv::setNumThreads(1);
  FeatureOptions options;
  options.type = type;
  options.kaze.single_pass = kaze_single_pass;
  if (type == "superpoint") options.superpoint.model_path = std::getenv("DUSKMAP_SUPERPOINT_ONNX");
  if (type == "onnx") {
    const std::string path = std::getenv("DUSKMAP_ONNX_FEATURES");
    JsonFields fields(ReadJsonFile(path), path);
    JsonCodecReader::ReadFields(fields, &options.onnx);
  }
  const auto extractor = CreateFeatureExtractor(options);
  size_t keypoints = 0;
  for (auto _ : state) {
    const FrameFeatures f = extractor->Extract(Frame());
    keypoints = f.size();
    benchmark::DoNotOptimize(f.descriptors.data);
  }
  state.counters["keypoints"] = static_cast<double>(keypoints);
}

// The descriptor time of `type` (sift or dusknet) on the frame's strongest
// 1,000 SIFT keypoints, detected before the timing.
void BM_Describe(benchmark::State& state, const std::string& type) {
  cv::setNumThreads(1);
  FeatureOptions options;
  options.max_features = 1000;
  options.type = FeatureTypeName(FeatureTypeId::kDuskNet);
  if (const char* model = std::getenv("DUSKMAP_DUSKNET_ONNX")) options.dusknet.model_path = model;
  cv::Mat gray;
  cv::cvtColor(Frame(), gray, cv::COLOR_BGR2GRAY);
  const cv::Ptr<cv::Feature2D> sift = CreateSiftFeature2D(options.sift, options.max_features);
  const std::vector<cv::KeyPoint> keypoints = DetectStrongest(*sift, gray, options.max_features);
  const auto extractor = CreateFeatureExtractor(options);
  const auto& dusknet = dynamic_cast<const OnnxPatchExtractor&>(*extractor);
  for (auto _ : state) {
    cv::Mat descriptors;
    if (type == "sift") {
      std::vector<cv::KeyPoint> described = keypoints;
      sift->compute(gray, described, descriptors);
    } else {
      descriptors = dusknet.Describe(gray, keypoints);
    }
    benchmark::DoNotOptimize(descriptors.data);
  }
  state.counters["keypoints"] = static_cast<double>(keypoints.size());
}

FrameFeatures RandomSuperPointLike(int count, uint64_t seed) {
  cv::RNG rng(seed);
  FrameFeatures f;
  f.descriptors.create(count, 256, CV_32F);
  rng.fill(f.descriptors, cv::RNG::NORMAL, 0.0, 1.0);
  for (int i = 0; i < count; ++i) {
    cv::Mat row = f.descriptors.row(i);
    row /= cv::norm(row);
    f.keypoints.emplace_back(cv::Point2f(rng.uniform(0.0f, 640.0f), rng.uniform(0.0f, 480.0f)),
                             8.0f, -1.0f, rng.uniform(0.01f, 1.0f));
  }
  return f;
}

void BM_SuperGlueMatch(benchmark::State& state) {
  SuperGlueOptions options;
  options.model_path = std::getenv("DUSKMAP_SUPERGLUE_ONNX");
  const SuperGlueMatcher matcher(options);
  const int n = static_cast<int>(state.range(0));
  // b sees a's keypoints shifted by 5 px with noisy descriptors.
  const FrameFeatures a = RandomSuperPointLike(n, 1);
  FrameFeatures b = RandomSuperPointLike(n, 2);
  for (int i = 0; i < n; ++i) {
    b.keypoints[i].pt = a.keypoints[i].pt + cv::Point2f(5.0f, 0.0f);
    cv::Mat row = b.descriptors.row(i);
    row = a.descriptors.row(i) + 0.05 * row;
    row /= cv::norm(row);
  }
  const cv::Size image(640, 480);
  size_t matches = 0;
  for (auto _ : state) {
    matches = matcher.Match(a, image, b, image).size();
    benchmark::ClobberMemory();
  }
  state.counters["matches"] = static_cast<double>(matches);
}

void BM_ImportH5(benchmark::State& state, bool binary) {
  constexpr int kFrames = 100;
  constexpr int kFeatures = 1000;
  const std::string path = bench::BenchTempPath("import.h5");
  {
    H5FeatureFile file(path, H5FeatureFile::Mode::kCreate);
    for (int i = 0; i < kFrames; ++i) {
      FrameFeatures f = RandomSuperPointLike(kFeatures, 10 + i);
      cv::Mat descriptors(kFeatures, binary ? 32 : 128, binary ? CV_8U : CV_32F);
      cv::randu(descriptors, 0, binary ? 256 : 1);
      file.Write("1/rgb/" + std::to_string(i) + ".png", f.keypoints, descriptors,
                 binary ? DescriptorKind::kBinary : DescriptorKind::kFloat);
    }
    file.Close();
  }
  FeatureOptions options;
  options.type = "h5";
  options.h5.path = path;
  options.h5.descriptor_kind = binary ? "binary" : "float";
  const auto extractor = CreateFeatureExtractor(options);
  RgbdFrame frame;
  frame.bgr = Frame();
  frame.depth_m = cv::Mat(480, 640, CV_32F, cv::Scalar(2.0f));
  frame.camera.width = 640;
  frame.camera.height = 480;
  frame.camera.fx = frame.camera.fy = 525.0;
  frame.camera.cx = 319.5;
  frame.camera.cy = 239.5;
  frame.session = "1";
  int i = 0;
  size_t keypoints = 0;
  for (auto _ : state) {
    frame.image_name = "rgb/" + std::to_string(i++ % kFrames) + ".png";
    const FrameFeatures f = extractor->ExtractFrame(frame);
    keypoints = f.size();
    benchmark::DoNotOptimize(f.descriptors.data);
  }
  state.counters["keypoints"] = static_cast<double>(keypoints);
  std::filesystem::remove(path);
}

const bool kRegistered = [] {
  benchmark::RegisterBenchmark("ImportH5/float128", BM_ImportH5, false)->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("ImportH5/binary32", BM_ImportH5, true)->Unit(benchmark::kMillisecond);
  for (const std::string& type : FeatureTypeNames()) {
    if (type == "superpoint" && std::getenv("DUSKMAP_SUPERPOINT_ONNX") == nullptr) continue;
    if (type == "onnx" && std::getenv("DUSKMAP_ONNX_FEATURES") == nullptr) continue;
    if (type == "h5") continue;  // imported, not detected: ImportH5 above
    benchmark::RegisterBenchmark(("Extract/" + type).c_str(), BM_Extract, type, false)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
  }
  benchmark::RegisterBenchmark("Extract/kaze/single_pass", BM_Extract, std::string("kaze"), true)
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime();
  for (const char* type : {"sift", "dusknet"}) {
    benchmark::RegisterBenchmark((std::string("Describe/") + type).c_str(), BM_Describe,
                                 std::string(type))
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
  }
  if (std::getenv("DUSKMAP_SUPERGLUE_ONNX") != nullptr) {
    benchmark::RegisterBenchmark("SuperGlueMatch", BM_SuperGlueMatch)
        ->Arg(1000)
        ->MeasureProcessCPUTime()
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
  }
  return true;
}();

}  // namespace
}  // namespace duskmap

BENCHMARK_MAIN();
