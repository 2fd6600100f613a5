// libFuzzer target for the sequence layouts of `duskmap features eval`
// (image_sequence.h): the input becomes a folder, which FindImageSequences
// reads in the layout byte 0 names; a pair list, when the input has one, is
// then applied with SelectSequencePairs.
//   byte 0: layout (0 or 3: detected, 1: homography, 2: static)
//   then files, each "@@<relative path>\n<contents>" (a section ends where the
//   next line starting with "@@" begins; its last newline is not part of it).
//   The section "@@!pairs" is not a file: its contents are a `--pairs-file`
//   list. Paths are restricted to [A-Za-z0-9._-/] without ".." or a leading
//   "/". Images are not decoded here, so their contents do not matter.
// Reading may throw duskmap::Error, one line; anything else (a crash, a
// sanitizer report, an abort) is a bug, as is a result that breaks what
// image_sequence.h promises: at least one sequence, each with two or more
// images of distinct indices and at least one pair of two of its
// images; homography pairs finite, static ones the identity; the reference
// (img1 in the homography layout, the first image in the static one) paired
// with every other image unless pairs were selected.
// With DUSKMAP_FUZZ_WRITE_SEEDS=<dir>, the target writes seed inputs there.
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <set>
#include <string>
#include <system_error>
#include <vector>

#include "slam/core/check.h"
#include "slam/features/eval/eval_pairs.h"
#include "slam/features/eval/image_sequence.h"
#include "tests/fuzz/fuzz_files.h"

namespace {

namespace fs = std::filesystem;

std::string Root() {
  const char* dir = std::getenv("TMPDIR");
  return std::string(dir ? dir : "/tmp") + "/duskmap_sequence_fuzz_" + std::to_string(getpid());
}

// Writes the input's files under `root`; returns the "!pairs" section, if any.
std::optional<std::string> WriteFolder(const std::string& text, const std::string& root) {
  std::optional<std::string> pairs;
  duskmap::fuzz::ForEachSection(text, [&](const std::string& path, size_t begin, size_t end) {
    if (path == "!pairs") {
      pairs = text.substr(begin, end - begin);
    } else if (duskmap::fuzz::SafePath(path)) {
      duskmap::fuzz::WriteBytes(root + "/" + path, text.data() + begin, end - begin);
    }
  });
  return pairs;
}

bool Finite(const cv::Matx33d& m) {
  for (const double v : m.val) {
    if (!std::isfinite(v)) return false;
  }
  return true;
}

void CheckOneLine(const duskmap::Error& e) {
  if (std::string(e.what()).find('\n') != std::string::npos) std::abort();
}

void CheckSequence(const duskmap::ImageSequence& sequence, duskmap::SequenceLayout layout, bool selected) {
  using namespace duskmap;
  if (sequence.layout != layout || sequence.images.size() < 2 || sequence.pairs.empty()) std::abort();
  std::set<int> indices;
  for (const SequenceImage& image : sequence.images) {
    // img0 is read as index 0 (which --pairs cannot name: docs/real_data.md, "Fuzzing").
    if (image.index < 0 || !indices.insert(image.index).second) std::abort();
  }
  if (!selected && sequence.pairs.size() != sequence.images.size() - 1) std::abort();
  for (const SequencePair& pair : sequence.pairs) {
    if (sequence.Image(pair.first_index) == nullptr || sequence.Image(pair.second_index) == nullptr ||
        pair.first_index == pair.second_index || !Finite(pair.second_from_first)) {
      std::abort();
    }
    const int reference = layout == SequenceLayout::kHomography ? 1 : sequence.images[0].index;
    if (!selected && pair.first_index != reference) std::abort();
    if (layout == SequenceLayout::kStatic && pair.second_from_first != cv::Matx33d::eye()) std::abort();
  }
}

std::string Section(const std::string& path, const std::string& contents) {
  return "@@" + path + "\n" + contents + "\n";
}

void WriteSeeds(const std::string& dir) {
  const std::string shift2 = "1 0 2\n0 1 0\n0 0 1\n";
  const std::string shift3 = "1 0 3\n0 1 0\n0 0 1\n";
  const std::string seeds[] = {
      // One homography sequence at the root.
      std::string(1, '\0') + Section("img1.ppm", "P6") + Section("img2.ppm", "P6") +
          Section("img3.ppm", "P6") + Section("H1to2p", shift2) + Section("H1to3p", shift3),
      // Two homography sequences, a direct H2to3p and a pair list.
      std::string(1, '\0') + Section("a/img1.png", "") + Section("a/img2.png", "") +
          Section("a/img3.png", "") +
          Section("a/H1to2p", shift2) + Section("a/H1to3p", shift3) + Section("a/H2to3p", shift2) +
          Section("b/img1.png", "") + Section("b/img2.png", "") + Section("b/H1to2p", shift2) +
          Section("!pairs", "# day -> night\n2-3\nb/2-1, a/3-1\n"),
      // Static: a webcam's frames with other names, and imgN ones.
      std::string(1, '\2') + Section("cam/0800.jpg", "") + Section("cam/2000.jpg", "") +
          Section("cam/2300.JPG", "") + Section("park/img1.bmp", "") + Section("park/img4.bmp", ""),
      // Detected static, with a selection.
      std::string(1, '\0') + Section("img1.pgm", "") + Section("img2.pgm", "") + Section("img3.pgm", "") +
          Section("!pairs", "2-3,3-1\n"),
  };
  int i = 0;
  for (const std::string& seed : seeds) {
    std::ofstream(dir + "/seed" + std::to_string(i++), std::ios::binary) << seed;
  }
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  if (const char* dir = std::getenv("DUSKMAP_FUZZ_WRITE_SEEDS")) WriteSeeds(dir);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace duskmap;
  const std::string root = Root();
  std::error_code error;
  fs::remove_all(root, error);
  fs::create_directories(root, error);
  const int layout_byte = size > 0 ? data[0] % 4 : 0;
  const std::optional<SequenceLayout> layout =
      layout_byte == 1 ? std::optional(SequenceLayout::kHomography)
                       : layout_byte == 2 ? std::optional(SequenceLayout::kStatic) : std::nullopt;
  const std::optional<std::string> pairs =
      WriteFolder(size > 0 ? std::string(reinterpret_cast<const char*>(data) + 1, size - 1) : "", root);
  try {
    SequenceSet set = FindImageSequences(root, layout);
    if (set.sequences.empty() || set.detected != !layout.has_value() || (layout && set.layout != *layout)) {
      std::abort();
    }
    for (const ImageSequence& sequence : set.sequences) CheckSequence(sequence, set.layout, false);
    if (pairs) {
      SelectSequencePairs(ParsePairListText(*pairs, "pairs.txt"), &set.sequences);
      for (const ImageSequence& sequence : set.sequences) CheckSequence(sequence, set.layout, true);
    }
  } catch (const Error& e) {
    CheckOneLine(e);
  }
  fs::remove_all(root, error);
  return 0;
}
