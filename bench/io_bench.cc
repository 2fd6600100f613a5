// Reading speed of real-data frames: decoding one 640x480 JPEG colour image
// plus its depth (RVL, 16-bit PNG, or lower-resolution depth registered to
// the colour image) into an RgbdFrame, on one core. Target: < 10 ms a frame.
// The colour image is a real photo (../shared Oxford "leuven" img1, resized)
// when available, else a synthetic textured pattern.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <optional>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "slam/datasets/camera_calibration.h"
#include "slam/datasets/frame_assembly.h"
#include "slam/datasets/image_blob.h"
#include "slam/datasets/rtabmap_db_reader.h"
#include "slam/datasets/rvl_codec.h"

namespace duskmap {
namespace {

cv::Mat ColourImage() {
  const std::string photo =
      std::string(DUSKMAP_SHARED_DIR) + "/data/illumination/oxford-leuven/img1.ppm";
  cv::Mat bgr = std::filesystem::exists(photo) ? cv::imread(photo, cv::IMREAD_COLOR) : cv::Mat();
  if (bgr.empty()) {
    bgr.create(480, 640, CV_8UC3);
    cv::randu(bgr, 0, 255);
    cv::GaussianBlur(bgr, bgr, cv::Size(0, 0), 2.0);
  }
  cv::resize(bgr, bgr, cv::Size(640, 480), 0, 0, cv::INTER_AREA);
  return bgr;
}

// A room-like depth: two planes with 2 mm noise and 5 % holes, in mm.
cv::Mat DepthImage(int width, int height) {
  cv::Mat depth(height, width, CV_16UC1);
  cv::RNG rng(1);
  for (int r = 0; r < height; ++r) {
    for (int c = 0; c < width; ++c) {
      const double plane = c < width / 2 ? 1500.0 + 2.0 * r : 2500.0 - 1.5 * c;
      const bool hole = rng.uniform(0.0, 1.0) < 0.05;
      depth.at<uint16_t>(r, c) = hole ? 0 : static_cast<uint16_t>(plane + rng.gaussian(2.0));
    }
  }
  return depth;
}

CameraCalibration Calibration() {
  CameraCalibration calibration;
  calibration.image_width = 640;
  calibration.image_height = 480;
  calibration.camera_matrix << 525.0, 0.0, 319.5, 0.0, 525.0, 239.5, 0.0, 0.0, 1.0;
  return calibration;
}

enum class DepthKind { kRvl, kPng, kRvlHalfResolution };

void BM_DecodeFrame640x480(benchmark::State& state, DepthKind kind) {
  std::vector<uint8_t> jpeg;
  cv::imencode(".jpg", ColourImage(), jpeg, {cv::IMWRITE_JPEG_QUALITY, 95});
  const cv::Mat depth = kind == DepthKind::kRvlHalfResolution ? DepthImage(320, 240)
                                                              : DepthImage(640, 480);
  std::vector<uint8_t> depth_blob;
  if (kind == DepthKind::kPng) {
    cv::imencode(".png", depth, depth_blob);
  } else {
    depth_blob = EncodeRvlBlob(depth);
  }
  const CameraCalibration calibration = Calibration();
  FrameAssembler assembler;
  for (auto _ : state) {
    RgbdFrame frame;
    const cv::Mat bgr = DecodeColorBlob(jpeg.data(), jpeg.size(), "jpeg");
    const cv::Mat depth_m = DecodeDepthBlob(depth_blob.data(), depth_blob.size(), "depth");
    assembler.Assemble(bgr, depth_m, calibration, "frame", &frame);
    benchmark::DoNotOptimize(frame.depth_m.data);
  }
  state.counters["jpeg_KiB"] = jpeg.size() / 1024.0;
  state.counters["depth_KiB"] = depth_blob.size() / 1024.0;
}
BENCHMARK_CAPTURE(BM_DecodeFrame640x480, jpeg_rvl, DepthKind::kRvl)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_DecodeFrame640x480, jpeg_png16, DepthKind::kPng)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_DecodeFrame640x480, jpeg_rvl_depth320x240, DepthKind::kRvlHalfResolution)
    ->Unit(benchmark::kMillisecond);

void BM_RvlDecode640x480(benchmark::State& state) {
  const std::vector<uint8_t> blob = EncodeRvlBlob(DepthImage(640, 480));
  for (auto _ : state) {
    benchmark::DoNotOptimize(DecodeRvlBlob(blob.data(), blob.size(), "depth").data);
  }
}
BENCHMARK(BM_RvlDecode640x480)->Unit(benchmark::kMillisecond);

// Whole reader path on the shared RTAB-Map database (SQLite read, 320x240).
void BM_ReadRtabmapDbFrame(benchmark::State& state) {
  const std::string db = std::string(DUSKMAP_SHARED_DIR) + "/data/rtabmap/rtabmap-db/session_small.db";
  if (!std::filesystem::exists(db)) {
    state.SkipWithError("shared RTAB-Map fixtures not found");
    return;
  }
  const auto reader = OpenRtabmapDatabase(db);
  const auto session = reader->OpenSession("session_small");
  for (auto _ : state) {
    std::optional<RgbdFrame> frame = session->Next();
    if (!frame) {
      session->Rewind();
      frame = session->Next();
    }
    benchmark::DoNotOptimize(frame->bgr.data);
  }
}
BENCHMARK(BM_ReadRtabmapDbFrame)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace duskmap

BENCHMARK_MAIN();
