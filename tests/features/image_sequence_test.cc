#include "slam/features/eval/image_sequence.h"

#include <filesystem>
#include <fstream>
#include <optional>

#include <gtest/gtest.h>

#include "slam/core/check.h"
#include "tests/features/static_scene.h"
#include "tests/testing/error_of.h"
#include "tests/testing/temp_dir.h"

namespace duskmap {
namespace {
namespace fs = std::filesystem;

using testing::ErrorOf;

void WriteHomography(const fs::path& path, const cv::Matx33d& h) {
  std::ofstream out(path);
  out.precision(17);
  for (int i = 0; i < 9; ++i) out << h.val[i] << (i % 3 == 2 ? "\n" : " ");
}

cv::Matx33d Shift(double dx) { return {1, 0, dx, 0, 1, 0, 0, 0, 1}; }

// img1..img<count> with H1toNp for every N >= 2 (a shift of N px).
fs::path HomographySequenceFolder(const fs::path& dir, int count) {
  testing::WriteStaticScene(dir, count);
  for (int n = 2; n <= count; ++n) WriteHomography(dir / ("H1to" + std::to_string(n) + "p"), Shift(n));
  return dir;
}

TEST(ImageSequence, LayoutIsDetectedFromTheHFiles) {
  const fs::path root = testing::ProcessTempDir("sequence_layouts");
  const fs::path with_h = HomographySequenceFolder(root / "with_h", 3);
  const SequenceSet homography = FindImageSequences(with_h.string(), std::nullopt);
  EXPECT_EQ(homography.layout, SequenceLayout::kHomography);
  ASSERT_EQ(homography.sequences[0].pairs.size(), 2u);
  EXPECT_EQ(homography.sequences[0].pairs[1].second_from_first, Shift(3));

  testing::WriteStaticScene(root / "webcam", 3);
  const SequenceSet fixed = FindImageSequences((root / "webcam").string(), std::nullopt);
  EXPECT_EQ(fixed.layout, SequenceLayout::kStatic);
  EXPECT_TRUE(fixed.detected);
  ASSERT_EQ(fixed.sequences[0].pairs.size(), 2u);
  EXPECT_EQ(fixed.sequences[0].pairs[0].second_from_first, cv::Matx33d::eye());
  EXPECT_EQ(fixed.sequences[0].pairs[1].second_index, 3);

  // Forced: static ignores the H files; homography needs them.
  const SequenceSet forced = FindImageSequences(with_h.string(), SequenceLayout::kStatic);
  EXPECT_FALSE(forced.detected);
  EXPECT_EQ(forced.sequences[0].pairs[1].second_from_first, cv::Matx33d::eye());
  EXPECT_EQ(ErrorOf([&] { FindImageSequences((root / "webcam").string(), SequenceLayout::kHomography); }),
            (root / "webcam" / "H1to2p").string() +
                ": missing (img2.png has no homography; a sequence with H files needs H1toNp for each imgN, or "
                "--layout static for a fixed camera)");
}

// Some H files but not all: an error naming the missing file, never a
// static sequence.
TEST(ImageSequence, AHomographySequenceMissingAFileIsNamed) {
  const fs::path root = testing::ProcessTempDir("sequence_missing");
  const fs::path dir = HomographySequenceFolder(root / "leuven", 4);
  fs::remove(dir / "H1to3p");
  EXPECT_EQ(ErrorOf([&] { FindImageSequences(dir.string(), std::nullopt); }),
            (dir / "H1to3p").string() +
                ": missing (img3.png has no homography; a sequence with H files needs H1toNp for each imgN, or "
                "--layout static for a fixed camera)");
  WriteHomography(dir / "H1to3p", Shift(3));
  fs::remove(dir / "img4.png");
  EXPECT_EQ(ErrorOf([&] { FindImageSequences(dir.string(), std::nullopt); }),
            (dir / "img4").string() + ".{ppm,png,jpg,jpeg,pgm,bmp}: missing (H1to4p names it)");
  fs::remove(dir / "H1to4p");
  EXPECT_EQ(FindImageSequences(dir.string(), std::nullopt).sequences[0].pairs.size(), 2u);
  // A folder of sequences where one has no H file at all: refused, naming it.
  testing::WriteStaticScene(root / "webcam", 2);
  EXPECT_EQ(ErrorOf([&] { FindImageSequences(root.string(), std::nullopt); }),
            (root / "webcam").string() + ": no H1toNp file, while " + dir.string() +
                " has them (a homography sequence needs H1toNp for each imgN; --layout static evaluates every "
                "sequence as a fixed camera)");
  const SequenceSet all_static = FindImageSequences(root.string(), SequenceLayout::kStatic);
  ASSERT_EQ(all_static.sequences.size(), 2u);
  EXPECT_EQ(all_static.sequences[0].name, "leuven");
  EXPECT_EQ(all_static.sequences[1].name, "webcam");
}

TEST(ImageSequence, StaticImagesWithOtherNamesAreNumberedInNameOrder) {
  const fs::path dir = fs::path(testing::ProcessTempDir("sequence_names")) / "cam";
  testing::WriteStaticScene(dir, 3, {"2026-06-01_1200.jpg", "2026-06-01_0600.png", "2026-06-01_2300.png"});
  std::ofstream(dir / "notes.txt") << "not an image";
  const ImageSequence seq = ReadImageSequence(dir.string(), SequenceLayout::kStatic);
  ASSERT_EQ(seq.images.size(), 3u);
  EXPECT_EQ(fs::path(seq.images[0].path).filename().string(), "2026-06-01_0600.png");
  EXPECT_EQ(fs::path(seq.images[1].path).filename().string(), "2026-06-01_1200.jpg");
  EXPECT_EQ(seq.images[2].index, 3);
  ASSERT_EQ(seq.pairs.size(), 2u);
  EXPECT_EQ(seq.pairs[1].first_index, 1);
  EXPECT_EQ(seq.pairs[1].second_index, 3);
}

TEST(ImageSequence, BadFoldersAreNamedInOneLine) {
  const fs::path root = testing::ProcessTempDir("sequence_bad");
  testing::WriteStaticScene(root / "twice", 2);
  fs::copy_file(root / "twice" / "img1.png", root / "twice" / "img1.ppm");
  EXPECT_EQ(ErrorOf([&] { ReadImageSequence((root / "twice").string(), SequenceLayout::kStatic); }),
            (root / "twice").string() + ": img1.png and img1.ppm are both image 1");
  testing::WriteStaticScene(root / "one", 1);
  EXPECT_EQ(ErrorOf([&] { ReadImageSequence((root / "one").string(), SequenceLayout::kStatic); }),
            (root / "one").string() +
                ": 1 image(s); a fixed camera's sequence needs two or more (img1, img2, ... or any names)");
  const fs::path bad_h = HomographySequenceFolder(root / "bad_h", 2);
  std::ofstream(bad_h / "H1to2p") << "1 0 0\n0 1 0\n0 0 nan\n";
  EXPECT_EQ(ErrorOf([&] { ReadImageSequence(bad_h.string(), SequenceLayout::kHomography); }),
            (bad_h / "H1to2p").string() + ": expected 9 finite numbers");
  EXPECT_EQ(ErrorOf([&] { FindImageSequences((root / "nothing").string(), std::nullopt); }),
            (root / "nothing").string() + ": not a directory");
}

// Found by a hand-written input to tests/fuzz/homography_file_fuzz's check
// (the fuzzer's own runs did not reach it): entries near the double range
// passed the determinant check (an infinite determinant) and gave a
// homography whose inverse was NaN.
TEST(ImageSequence, HomographiesOutOfRangeAreRefused) {
  const cv::Matx33d h = ParseHomography(" 0.88 0.31 -39.4\n-0.18 0.94 153.2\n1.96e-4 -1.6e-5 1\n", "H1to2p");
  EXPECT_EQ(h(1, 2), 153.2);
  EXPECT_EQ(ErrorOf([] { ParseHomography("1 0 0 0 1 0 0 0", "H1to2p"); }), "H1to2p: expected 9 finite numbers");
  EXPECT_EQ(ErrorOf([] { ParseHomography("1 0 0 0 1 0 0 0 1e-13", "H1to2p"); }), "H1to2p: singular homography");
  for (const char* text : {"1e200 0 0 0 1e200 0 0 0 1e200", "1e300 1e300 0 0 1 0 0 0 1e10"}) {
    EXPECT_EQ(ErrorOf([&] { ParseHomography(text, "H1to2p"); }),
              "H1to2p: homography out of range (its determinant or inverse is not finite)");
  }
  const fs::path root = testing::ProcessTempDir("sequence_range");
  const fs::path huge = HomographySequenceFolder(root / "huge", 2);
  std::ofstream(huge / "H1to2p") << "1e200 0 0\n0 1e200 0\n0 0 1e200\n";
  EXPECT_EQ(ErrorOf([&] { ReadImageSequence(huge.string(), SequenceLayout::kHomography); }),
            (huge / "H1to2p").string() + ": homography out of range (its determinant or inverse is not finite)");

  // Each file in range, their composition for pair 2-3 (H1to3 * H1to2^-1) not.
  const fs::path composed = HomographySequenceFolder(root / "composed", 3);
  WriteHomography(composed / "H1to2p", {1e-200, 0, 0, 0, 1e200, 0, 0, 0, 1});
  WriteHomography(composed / "H1to3p", {1e200, 0, 0, 0, 1, 0, 0, 0, 1e-200});
  std::vector<ImageSequence> sequences = {ReadImageSequence(composed.string(), SequenceLayout::kHomography)};
  EXPECT_EQ(ErrorOf([&] { SelectSequencePairs(ParsePairList("2-3"), &sequences); }),
            composed.string() + ": pair '2-3' composed as H1to3p * H1to2p^-1 is not finite (entries out of range)");
  EXPECT_EQ(sequences[0].pairs.size(), 2u);  // left as it was
}

TEST(ImageSequence, PairSelection) {
  const fs::path root = testing::ProcessTempDir("sequence_pairs");
  HomographySequenceFolder(root / "a", 4);
  HomographySequenceFolder(root / "b", 3);
  WriteHomography(root / "a" / "H2to4p", Shift(7));  // a direct file wins over the composition
  std::vector<ImageSequence> sequences = FindImageSequences(root.string(), std::nullopt).sequences;
  SelectSequencePairs(ParsePairList("1-3, a/2-4, a/4-2"), &sequences);
  ASSERT_EQ(sequences.size(), 2u);
  ASSERT_EQ(sequences[0].pairs.size(), 3u);
  EXPECT_EQ(sequences[0].pairs[0].second_from_first, Shift(3));
  EXPECT_EQ(sequences[0].pairs[1].second_from_first, Shift(7));
  const cv::Matx33d composed = sequences[0].pairs[2].second_from_first;  // H1to2 * H1to4^-1
  EXPECT_NEAR(composed(0, 2), -2.0, 1e-12);
  ASSERT_EQ(sequences[1].pairs.size(), 1u);
  EXPECT_EQ(sequences[1].pairs[0].second_index, 3);

  // Only one sequence's pairs: the other is dropped.
  sequences = FindImageSequences(root.string(), std::nullopt).sequences;
  SelectSequencePairs(ParsePairList("b/2-3"), &sequences);
  ASSERT_EQ(sequences.size(), 1u);
  EXPECT_EQ(sequences[0].name, "b");

  sequences = FindImageSequences(root.string(), std::nullopt).sequences;
  EXPECT_EQ(ErrorOf([&] { SelectSequencePairs(ParsePairList("1-2,1-4"), &sequences); }),
            "--pairs: pair '1-4' does not exist in sequence b (no image 4; images 1, 2, 3)");
  EXPECT_EQ(ErrorOf([&] { SelectSequencePairs(ParsePairList("c/1-2"), &sequences); }),
            "--pairs: pair 'c/1-2': no sequence 'c' (sequences: a, b)");
  EXPECT_EQ(ErrorOf([&] { SelectSequencePairs(ParsePairList("1_2"), &sequences); }),
            "--pairs: '1_2' is not an image pair <i>-<j> or <sequence>/<i>-<j> (imgN's N, from 1)");
}

}  // namespace
}  // namespace duskmap
