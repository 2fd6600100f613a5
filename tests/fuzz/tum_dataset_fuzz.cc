// libFuzzer target for the TUM-layout and synthetic dataset readers
// (OpenTumDataset, OpenSyntheticDataset): the input becomes a dataset folder,
// which both readers open; every session is listed and every frame read, then
// the first frame again after Rewind.
//   byte 0: flags (bit 0: TumReadOptions::allow_unordered)
//   then files, each "@@<relative path>\n<contents>" (a section ends where the
//   next line starting with "@@" begins; its last newline is not part of it).
// Before the files are written the folder holds tiny images that index files
// may list: rgb/0.png..rgb/2.png (8x6 BGR) and depth/0.png..depth/2.png (8x6
// 16-bit), at the top and in the session folder "1"; a file of the input with
// the same path replaces one. Paths are restricted to [A-Za-z0-9._-/] without
// ".." or a leading "/".
// Opening and reading may throw duskmap::Error; anything else (a crash, a
// sanitizer report, an abort) is a bug, as is a frame that breaks what the
// readers promise (8-bit BGR and float depth of one size, the size of valid
// intrinsics, finite poses, as many frames as the session said).
// With DUSKMAP_FUZZ_WRITE_SEEDS=<dir>, the target writes seed inputs there.
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <string>
#include <system_error>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "slam/core/check.h"
#include "slam/io/synthetic_dataset.h"
#include "slam/io/tum_dataset.h"
#include "tests/fuzz/fuzz_files.h"

namespace {

// DUSKMAP_FUZZ_VERBOSE=1: print each expected error (to see how far an input gets).
void Expected(const duskmap::Error& e) {
  static const bool verbose = std::getenv("DUSKMAP_FUZZ_VERBOSE") != nullptr;
  if (verbose) std::fprintf(stderr, "%s: %s\n", "tum_dataset_fuzz", e.what());
}

namespace fs = std::filesystem;
using Bytes = std::vector<uint8_t>;

constexpr int kImages = 3;

std::string Root() {
  const char* dir = std::getenv("TMPDIR");
  return std::string(dir ? dir : "/tmp") + "/duskmap_tum_fuzz_" + std::to_string(getpid());
}

struct ImageFiles {
  Bytes rgb[kImages];
  Bytes depth[kImages];
};

const ImageFiles& Images() {
  static const ImageFiles files = [] {
    ImageFiles f;
    for (int i = 0; i < kImages; ++i) {
      cv::Mat bgr(6, 8, CV_8UC3, cv::Scalar(40 * i, 90, 200 - 30 * i));
      cv::Mat depth(6, 8, CV_16UC1, cv::Scalar(1000 + 500 * i));
      depth.at<uint16_t>(0, 0) = 0;
      cv::imencode(".png", bgr, f.rgb[i]);
      cv::imencode(".png", depth, f.depth[i]);
    }
    return f;
  }();
  return files;
}

void WriteFolder(const uint8_t* data, size_t size, const std::string& root) {
  const ImageFiles& images = Images();
  for (const std::string& folder : {root, root + "/1"}) {
    for (int i = 0; i < kImages; ++i) {
      const std::string name = std::to_string(i) + ".png";
      duskmap::fuzz::WriteBytes(folder + "/rgb/" + name, reinterpret_cast<const char*>(images.rgb[i].data()),
                 images.rgb[i].size());
      duskmap::fuzz::WriteBytes(folder + "/depth/" + name, reinterpret_cast<const char*>(images.depth[i].data()),
                 images.depth[i].size());
    }
  }
  const std::string text(reinterpret_cast<const char*>(data), size);
  duskmap::fuzz::ForEachSection(text, [&](const std::string& path, size_t begin, size_t end) {
    if (duskmap::fuzz::SafePath(path)) duskmap::fuzz::WriteBytes(root + "/" + path, text.data() + begin, end - begin);
  });
}

bool Finite(const duskmap::Rigid3d& pose) { return pose.IsFinite(); }

void ReadEverything(const duskmap::DatasetReader& reader) {
  using namespace duskmap;
  for (const SessionInfo& info : reader.Sessions()) {
    const std::unique_ptr<SessionReader> session = reader.OpenSession(info.name);
    int64_t frames = 0;
    std::optional<double> first_timestamp;
    try {
      while (const std::optional<RgbdFrame> frame = session->Next()) {
        if (frame->bgr.type() != CV_8UC3 || frame->depth_m.type() != CV_32FC1 ||
            frame->bgr.size() != frame->depth_m.size() || !frame->camera.IsValid() ||
            frame->bgr.cols != frame->camera.width || frame->bgr.rows != frame->camera.height ||
            !std::isfinite(frame->timestamp_s) || !Finite(frame->odom_from_body) ||
            (frame->world_from_camera && !Finite(*frame->world_from_camera))) {
          std::abort();
        }
        static bool noted_depth = false;  // accepted, but worth a word (not a crash)
        if (!noted_depth && !cv::checkRange(frame->depth_m)) {
          noted_depth = true;
          std::fprintf(stderr, "tum_dataset_fuzz: note: a frame with non-finite depth was read\n");
        }
        if (!first_timestamp) first_timestamp = frame->timestamp_s;
        ++frames;
      }
      if (frames != session->info().num_frames) std::abort();
    } catch (const InputError& e) {
      Expected(e);
      continue;  // Next() stays on the bad frame: the session ends here
    }
    session->Rewind();
    const std::optional<RgbdFrame> again = session->Next();
    if (first_timestamp.has_value() != again.has_value() ||
        (again && again->timestamp_s != *first_timestamp)) {
      std::abort();
    }
  }
}

std::string Section(const std::string& path, const std::string& contents) {
  return "@@" + path + "\n" + contents + "\n";
}

std::string PngSection(const std::string& path, const Bytes& png) {
  return Section(path, std::string(png.begin(), png.end()));
}

void WriteSeeds(const std::string& dir) {
  const std::string calibration =
      R"({"width": 8, "height": 6, "fx": 10.0, "fy": 10.0, "cx": 3.5, "cy": 2.5, "depth_scale": 1000.0})";
  const std::string rgb = "# color images\n1700000000.000000 rgb/0.png\n"
                          "1700000000.033333 rgb/1.png\n1700000000.066667 rgb/2.png\n";
  const std::string depth = "1700000000.001000 depth/0.png\n1700000000.034000 depth/1.png\n"
                            "1700000000.067000 depth/2.png\n";
  const std::string trajectory = "# timestamp tx ty tz qx qy qz qw\n"
                                 "1699999999.99 0 0 0 0 0 0 1\n"
                                 "1700000000.03 0.1 0 0 0 0 0 1\n"
                                 "1700000000.07 0.2 0.01 0 0 0.0499792 0 0.99875\n";
  const std::string manifest =
      R"({"format": "duskmap-synthetic", "version": 1, "sessions": [)"
      R"({"name": "1", "folder": "1", "clock_time": "16:46", "role": "mapping"}]})";
  auto tum = [&](const std::string& prefix) {
    return Section(prefix + "rgb.txt", rgb) + Section(prefix + "depth.txt", depth) +
           Section(prefix + "groundtruth.txt", trajectory) +
           Section(prefix + "odometry.txt", trajectory) +
           Section(prefix + "calibration.json", calibration);
  };
  const std::string seeds[] = {
      std::string(1, '\0') + tum(""),
      std::string(1, '\0') + Section("manifest.json", manifest) + tum("1/"),
      // Unordered, with a duplicate line and an rgb image without depth.
      std::string(1, '\1') + Section("rgb.txt", "1700000000.066667 rgb/2.png\n" + rgb) +
          Section("depth.txt", depth) + Section("calibration.json", calibration),
      // The images themselves, to be mutated.
      std::string(1, '\0') + tum("") + PngSection("rgb/1.png", Images().rgb[1]) +
          PngSection("depth/2.png", Images().depth[2]),
  };
  int i = 0;
  for (const std::string& seed : seeds) {
    std::ofstream(dir + "/seed" + std::to_string(i++), std::ios::binary) << seed;
  }
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  Images();
  if (const char* dir = std::getenv("DUSKMAP_FUZZ_WRITE_SEEDS")) WriteSeeds(dir);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string root = Root();
  std::error_code error;
  fs::remove_all(root, error);
  fs::create_directories(root, error);
  WriteFolder(data + (size > 0 ? 1 : 0), size > 0 ? size - 1 : 0, root);
  duskmap::TumReadOptions options;
  options.allow_unordered = size > 0 && (data[0] & 1);
  try {
    ReadEverything(*duskmap::OpenTumDataset(root, options));
  } catch (const duskmap::Error& e) {
    Expected(e);
  }
  try {
    ReadEverything(*duskmap::OpenSyntheticDataset(root, options));
  } catch (const duskmap::Error& e) {
    Expected(e);
  }
  fs::remove_all(root, error);
  return 0;
}
