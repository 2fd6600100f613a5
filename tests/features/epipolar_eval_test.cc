#include "slam/features/eval/epipolar_eval.h"

#include <cmath>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "slam/core/check.h"
#include "slam/features/feature_factory.h"
#include "slam/features/h5_feature_file.h"
#include "tests/features/test_images.h"
#include "tests/testing/error_of.h"
#include "tests/testing/temp_dir.h"
#include "tests/features/two_plane_pair.h"

namespace duskmap {
namespace {
namespace fs = std::filesystem;

using testing::ErrorOf;
using testing::ProcessTempDir;

TEST(SymmetricEpipolarDistance, MeanOfTheTwoPointToLineDistances) {
  // Pure translation along x with identity intrinsics: epipolar lines are rows.
  const cv::Matx33d f(0, 0, 0, 0, 0, -1, 0, 1, 0);
  EXPECT_NEAR(SymmetricEpipolarDistancePx(f, {10, 5}, {30, 5}), 0.0, 1e-12);
  EXPECT_NEAR(SymmetricEpipolarDistancePx(f, {10, 5}, {30, 8}), 3.0, 1e-12);
  const testing::TwoPlanePair geometry;
  const cv::Point2d p1(100, 200);
  EXPECT_LT(SymmetricEpipolarDistancePx(geometry.f, p1, geometry.Map(p1)), 1e-9);
  EXPECT_LT(SymmetricEpipolarDistancePx(geometry.f, {500, 100}, geometry.Map({500, 100})), 1e-9);
}

TEST(EpipolarEval, TwoPlanePairIsSolvedAndAWrongGroundTruthIsNot) {
  const fs::path root = ProcessTempDir("epipolar_solve");
  const testing::TwoPlanePair geometry;
  geometry.Write(root / "scenes" / "planes");
  geometry.Write(root / "scenes" / "planes_wrong_truth", 25.0);
  geometry.Write(root / "top");
  const std::vector<CorrespondencePair> pairs = FindCorrespondencePairs(root.string());
  ASSERT_EQ(pairs.size(), 3u);
  EXPECT_EQ(pairs[0].name, "scenes/planes");
  EXPECT_EQ(pairs[0].category, "scenes");
  EXPECT_EQ(pairs[2].name, "top");
  EXPECT_EQ(pairs[2].category, "");
  EXPECT_GT(pairs[0].correspondences.size(), 100u);

  EpipolarEvalOptions options;
  options.types = {"sift", "orb"};
  const EpipolarEvalResult result = EvaluateOnCorrespondencePairs(pairs, options);
  ASSERT_EQ(result.types.size(), 2u);
  for (const EpipolarTypeSummary& t : result.types) {
    SCOPED_TRACE(t.type);
    ASSERT_EQ(t.records.size(), 3u);
    EXPECT_TRUE(t.records[0].estimated);
    EXPECT_GT(t.records[0].inliers, 50);
    EXPECT_LT(t.records[0].median_error_px, 2.0);
    EXPECT_LT(t.records[2].median_error_px, 2.0);
    // Half the truth is 25 px off its epipolar line: the median is >= 10 px.
    EXPECT_GT(t.records[1].median_error_px, 10.0);
    EXPECT_EQ(t.solved, (std::array<int, 3>{2, 2, 2}));
    EXPECT_EQ(t.solved_by_category.at("scenes"), (std::array<int, 3>{1, 1, 1}));
    EXPECT_EQ(t.pairs_by_category.at("scenes"), 2);
  }
  const std::string table = ToMarkdown(result);
  EXPECT_NE(table.find("| sift | 3 | 2 | 2 | 2 |"), std::string::npos) << table;
  // One row per type and pair: the wrong truth's pair is solved at no threshold.
  EXPECT_NE(table.find("| orb | scenes/planes | "), std::string::npos) << table;
  const size_t wrong = table.find("| sift | scenes/planes_wrong_truth | ");
  ASSERT_NE(wrong, std::string::npos) << table;
  EXPECT_NE(table.substr(wrong, table.find('\n', wrong) - wrong).find("| no / no / no |"), std::string::npos)
      << table;

  // --pairs by name: those pairs only, in the selection's order; an unknown one is named.
  const std::vector<CorrespondencePair> chosen =
      SelectCorrespondencePairs(pairs, ParsePairList("top,scenes/planes"));
  ASSERT_EQ(chosen.size(), 2u);
  EXPECT_EQ(chosen[0].name, "top");
  EXPECT_EQ(chosen[1].name, "scenes/planes");
  EXPECT_EQ(ErrorOf([&] { SelectCorrespondencePairs(pairs, ParsePairList("top,kremlin")); }),
            "--pairs: pair 'kremlin' does not exist (pairs: scenes/planes, scenes/planes_wrong_truth, top)");
  EXPECT_EQ(ToJson(result)["types"][0]["categories"]["scenes"]["solved"][2], 1);
}

// Every type is scored this way, the imported h5 one included: SIFT's
// features exported into "<pair name>/01.png" groups give SIFT's result.
TEST(EpipolarEval, ImportedFeaturesAreScoredLikeTheirSource) {
  const fs::path root = ProcessTempDir("epipolar_h5");
  testing::TwoPlanePair().Write(root / "planes");
  const std::vector<CorrespondencePair> pairs = FindCorrespondencePairs((root / "planes").string());
  ASSERT_EQ(pairs.size(), 1u);
  FeatureOptions sift;
  sift.type = "sift";
  const auto extractor = CreateFeatureExtractor(sift);
  const std::string h5 = (root / "sift.h5").string();
  {
    H5FeatureFile file(h5, H5FeatureFile::Mode::kCreate);
    for (const char* image : {"01.png", "02.png"}) {
      const FrameFeatures f = extractor->Extract(cv::imread((root / "planes" / image).string()));
      file.Write("planes/" + std::string(image), f.keypoints, f.descriptors, f.kind);
    }
    file.Close();
  }
  EpipolarEvalOptions options;
  options.types = {"sift", "h5"};
  options.features.h5.path = h5;
  const EpipolarEvalResult result = EvaluateOnCorrespondencePairs(pairs, options);
  EXPECT_EQ(result.types[1].records[0].matches, result.types[0].records[0].matches);
  EXPECT_EQ(result.types[1].records[0].median_error_px, result.types[0].records[0].median_error_px);
}

TEST(EpipolarEval, BadPairFoldersAreNamedInOneLine) {
  const fs::path root = ProcessTempDir("epipolar_bad");
  const fs::path pair = root / "pair";
  testing::TwoPlanePair().Write(pair);
  const std::string corrs = (pair / "corrs.txt").string();
  std::ofstream(corrs) << "1 2 3 4\n5 6 seven 8\n";
  EXPECT_EQ(ErrorOf([&] { FindCorrespondencePairs(pair.string()); }),
            corrs + ":2: expected four numbers 'x1 y1 x2 y2', got '5 6 seven 8'");
  std::ofstream(corrs) << "1 2 3 4 5\n";
  EXPECT_NE(ErrorOf([&] { FindCorrespondencePairs(pair.string()); }).find(corrs + ":1: expected four numbers"),
            std::string::npos);
  std::ofstream(corrs) << "\n";
  EXPECT_EQ(ErrorOf([&] { FindCorrespondencePairs(pair.string()); }), corrs + ": no correspondence");
  std::ofstream(corrs) << "10 10 700 10\n";
  const std::vector<CorrespondencePair> outside = FindCorrespondencePairs(pair.string());
  EpipolarEvalOptions options;
  options.types = {"orb"};
  EXPECT_EQ(ErrorOf([&] { EvaluateOnCorrespondencePairs(outside, options); }),
            corrs + ":1: correspondence (10, 10) -> (700, 10) lies outside the images (640x480, 640x480)");
  fs::remove(corrs);
  EXPECT_EQ(ErrorOf([&] { FindCorrespondencePairs(pair.string()); }),
            corrs + ": missing (the pair's correspondences; a fixed camera's images named 01, 02: --layout static)");
  EXPECT_TRUE(FindCorrespondencePairs((root / "nothing_here").string()).empty());
}

// A pair folder missing an image is an error naming the file, never skipped:
// pointed at directly, or found under the root or in a category folder.
TEST(EpipolarEval, APairFolderMissingAnImageIsNamed) {
  const fs::path root = ProcessTempDir("epipolar_missing");
  testing::TwoPlanePair().Write(root / "complete");
  testing::TwoPlanePair().Write(root / "night" / "halfway");
  fs::remove(root / "night" / "halfway" / "02.png");
  const std::string missing =
      (root / "night" / "halfway" / "02").string() +
      ".{png,jpg,jpeg,ppm,bmp}: missing (a pair folder holds 01.*, 02.* and corrs.txt)";
  EXPECT_EQ(ErrorOf([&] { FindCorrespondencePairs((root / "night" / "halfway").string()); }), missing);
  EXPECT_EQ(ErrorOf([&] { FindCorrespondencePairs(root.string()); }), missing);
  fs::rename(root / "night" / "halfway", root / "halfway");
  EXPECT_EQ(ErrorOf([&] { FindCorrespondencePairs(root.string()); }),
            (root / "halfway" / "02").string() +
                ".{png,jpg,jpeg,ppm,bmp}: missing (a pair folder holds 01.*, 02.* and corrs.txt)");
  fs::remove(root / "halfway" / "01.png");  // corrs.txt alone makes it a pair folder
  EXPECT_EQ(ErrorOf([&] { FindCorrespondencePairs(root.string()); }),
            (root / "halfway" / "01").string() +
                ".{png,jpg,jpeg,ppm,bmp}: missing (a pair folder holds 01.*, 02.* and corrs.txt)");
  // A fixed camera's images named 01, 02, 03 are not a pair folder.
  fs::remove_all(root / "halfway");
  const fs::path webcam = root / "webcam";
  fs::create_directories(webcam);
  for (const char* name : {"01.png", "02.png", "03.png"}) {
    cv::imwrite((webcam / name).string(), cv::Mat(8, 8, CV_8UC1, cv::Scalar(3)));
  }
  EXPECT_FALSE(IsCorrespondencePairFolder(webcam.string()));
  EXPECT_EQ(FindCorrespondencePairs(root.string()).size(), 1u);
}

}  // namespace
}  // namespace duskmap
