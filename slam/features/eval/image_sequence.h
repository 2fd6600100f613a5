// The image sequences of `duskmap features eval` and their two layouts:
//   homography: the Oxford/HPatches layout, img1 (the reference), img2..imgN
//               and H1toNp, the homography reference -> imgN (x_N ~ H x_1);
//   static:     a fixed camera (a webcam's day and night): the images alone,
//               every pair related by the identity, no H files.
// A folder holding H files is a homography sequence, one without is static
// (auto); a homography sequence must have H1toNp for every image and an
// image for every H1toNp, so that a missing file is an error, never a silent
// change of layout. Which pairs are scored: the reference with every other
// image, or the pairs selected by eval_pairs.h's "<i>-<j>".
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "slam/features/eval/eval_pairs.h"

namespace duskmap {

enum class SequenceLayout { kHomography, kStatic };

// "homography", "static".
const char* SequenceLayoutName(SequenceLayout layout);

struct SequenceImage {
  int index = 0;     // N of imgN, or the position in name order (static, other names)
  std::string path;
};

struct SequencePair {
  int first_index = 0;   // the reference side
  int second_index = 0;  // the target side
  cv::Matx33d second_from_first = cv::Matx33d::eye();  // x_second ~ H x_first
};

struct ImageSequence {
  std::string name;       // the folder's name
  std::string directory;
  SequenceLayout layout = SequenceLayout::kHomography;
  std::vector<SequenceImage> images;  // by index; images[0] is the reference
  std::vector<SequencePair> pairs;    // the reference with every other image, or the selection

  // The image with `index`, nullptr when the sequence has none.
  const SequenceImage* Image(int index) const;
};

// A homography file's text (H1toNp: 9 numbers, row-major, x_N ~ H x_1), as
// read by the homography layout; `path` names it in errors. InputError
// "<path>: expected 9 finite numbers", "<path>: singular homography" (|det| at
// most 1e-12) or, when its determinant or inverse overflows, "<path>:
// homography out of range ...".
cv::Matx33d ParseHomography(const std::string& text, const std::string& path);

// Whether `directory` holds a homography file (H<i>to<j>p).
bool HasHomographyFiles(const std::string& directory);

// Reads one sequence folder in `layout`. Image files: .ppm, .png, .jpg,
// .jpeg, .pgm, .bmp. InputError naming the missing file or the problem:
//   homography: no img1; an imgN (N >= 2) without H1toNp; an H1toNp without
//               imgN; no target; a malformed or singular H1toNp;
//   static:     fewer than two images. The images are the imgN ones when
//               there are any, else every image, numbered 1.. in name order.
// Two images with one index (img1.png and img1.ppm) are an error in both.
ImageSequence ReadImageSequence(const std::string& directory, SequenceLayout layout);

struct SequenceSet {
  SequenceLayout layout = SequenceLayout::kHomography;
  bool detected = false;  // true: chosen by the H files, not by the caller
  std::vector<ImageSequence> sequences;
};

// `root` itself when it is a sequence (it holds img1, or images and no
// sub-folder with images), else each sub-folder with images (sorted by
// name). `layout` empty: detected per folder, H files -> homography, none ->
// static; sequences of both kinds under one root are an InputError naming
// the one without H files. InputError when no sequence is found.
SequenceSet FindImageSequences(const std::string& root, std::optional<SequenceLayout> layout);

// Keeps only the selected pairs ("<i>-<j>" in every sequence,
// "<sequence>/<i>-<j>" in that one; sequences left without a pair are
// dropped). A homography pair i-j takes HitoJp when the folder has it, else
// H1toJp * H1toIp^-1 (InputError naming the folder and pair when that
// product is not finite); a static pair the identity. ConfigError naming the selector's
// origin when it names no sequence or an image the sequence lacks.
void SelectSequencePairs(const std::vector<PairSelector>& selectors, std::vector<ImageSequence>* sequences);

}  // namespace duskmap
