#include "slam/features/eval/sequence_eval.h"

#include <filesystem>
#include <fstream>
#include <optional>

#include <gtest/gtest.h>

#include "tests/features/static_scene.h"
#include "tests/features/test_images.h"
#include "tests/testing/error_of.h"

namespace duskmap {
namespace {
namespace fs = std::filesystem;

// A synthetic Oxford-layout sequence: img1 and rotated/darkened targets.
std::string WriteSyntheticSequence() {
  const fs::path dir = fs::path(DUSKMAP_BINARY_DIR) / "features_eval_synthetic" / "ramp";
  fs::create_directories(dir);
  const cv::Mat ref = testing::TexturedImage(320, 240, 11);
  cv::imwrite((dir / "img1.png").string(), ref);
  for (int n = 2; n <= 3; ++n) {
    cv::Matx33d h;
    cv::Mat target = testing::WarpRotateScale(ref, 5.0 * n, 1.0, &h);
    target.convertTo(target, CV_8U, 1.0 - 0.2 * n, 10.0);
    cv::imwrite((dir / ("img" + std::to_string(n) + ".png")).string(), target);
    std::ofstream out(dir / ("H1to" + std::to_string(n) + "p"));
    out.precision(17);
    for (int i = 0; i < 9; ++i) out << h.val[i] << (i % 3 == 2 ? "\n" : " ");
  }
  return dir.parent_path().string();
}

TEST(SequenceEvalTest, ReadsTheLayoutAndEvaluatesEveryPair) {
  const std::string root = WriteSyntheticSequence();
  const SequenceSet set = FindImageSequences(root, std::nullopt);
  EXPECT_EQ(set.layout, SequenceLayout::kHomography);
  EXPECT_TRUE(set.detected);
  const auto& sequences = set.sequences;
  ASSERT_EQ(sequences.size(), 1u);
  EXPECT_EQ(sequences[0].name, "ramp");
  ASSERT_EQ(sequences[0].pairs.size(), 2u);
  FeatureEvalOptions options;
  options.types = {"surf", "brief"};
  const FeatureEvalResult result = EvaluateFeatures(sequences, options);
  ASSERT_EQ(result.types.size(), 2u);
  for (const TypeSummary& s : result.types) {
    EXPECT_EQ(s.pairs, 2);
    EXPECT_GT(s.keypoints_per_image, 100.0);
    EXPECT_GT(s.repeatability, 0.5);
    EXPECT_GT(s.homography_accuracy, 0.99) << s.type;
    EXPECT_GE(s.mma[2], s.mma[1]);
    EXPECT_GE(s.mma[1], s.mma[0]);
    EXPECT_GT(s.extraction_ms, 0.0);
  }
  EXPECT_EQ(result.types[0].descriptor_bytes, 256);
  EXPECT_EQ(result.types[1].descriptor_bytes, 32);
  const nlohmann::json j = ToJson(result);
  EXPECT_EQ(j["layout"], "homography");
  EXPECT_EQ(j["types"].size(), 2u);
  ASSERT_EQ(j["types"][0]["pairs_detail"].size(), 2u);
  EXPECT_EQ(j["types"][0]["pairs_detail"][1]["reference"], 1);
  EXPECT_EQ(j["types"][0]["pairs_detail"][1]["target"], 3);
  EXPECT_EQ(j["types"][0]["pairs_detail"][1]["target_image"], "img3.png");
  const std::string md = ToMarkdown(result);
  EXPECT_NE(md.find("| surf |"), std::string::npos);
  EXPECT_NE(md.find("| brief |"), std::string::npos);
  // One row per type and pair below the summary.
  for (const char* row : {"| surf | ramp | 1-2 |", "| surf | ramp | 1-3 |", "| brief | ramp | 1-2 |",
                          "| brief | ramp | 1-3 |"}) {
    EXPECT_NE(md.find(row), std::string::npos) << row << "\n" << md;
  }
}

// A selected pair between two targets is scored through H1to3p * H1to2p^-1
// (the synthetic sequence has no H2to3p): a wrong composition would fail
// every homography.
TEST(SequenceEvalTest, SelectedPairsAreScoredWithTheirHomography) {
  SequenceSet set = FindImageSequences(WriteSyntheticSequence(), std::nullopt);
  SelectSequencePairs(ParsePairList("2-3,ramp/3-1"), &set.sequences);
  ASSERT_EQ(set.sequences.size(), 1u);
  FeatureEvalOptions options;
  options.types = {"sift"};
  const FeatureEvalResult result = EvaluateFeatures(set.sequences, options);
  const TypeSummary& sift = result.types[0];
  ASSERT_EQ(sift.records.size(), 2u);
  EXPECT_EQ(sift.records[0].reference_index, 2);
  EXPECT_EQ(sift.records[0].target_index, 3);
  EXPECT_EQ(sift.records[1].reference_index, 3);
  EXPECT_EQ(sift.records[1].target_index, 1);
  for (const PairRecord& r : sift.records) {
    EXPECT_TRUE(r.metrics.homography_correct) << r.reference_index << "-" << r.target_index;
    EXPECT_GT(r.metrics.repeatability, 0.5);
  }
  EXPECT_NE(ToMarkdown(result).find("| sift | ramp | 2-3 |"), std::string::npos);
}

// A fixed camera: the same view at falling light, no H files. The layout is
// detected and the identity is the ground truth: every homography found is
// correct and keypoints repeat as under a perfect homography.
TEST(SequenceEvalTest, StaticSceneIsDetectedAndScoredWithTheIdentity) {
  const fs::path dir = fs::path(DUSKMAP_BINARY_DIR) / "features_eval_static" / "webcam";
  fs::remove_all(dir);
  testing::WriteStaticScene(dir, 4);
  const SequenceSet set = FindImageSequences(dir.string(), std::nullopt);
  EXPECT_EQ(set.layout, SequenceLayout::kStatic);
  EXPECT_TRUE(set.detected);
  ASSERT_EQ(set.sequences.size(), 1u);
  ASSERT_EQ(set.sequences[0].pairs.size(), 3u);
  FeatureEvalOptions options;
  options.types = {"surf", "orb"};
  const FeatureEvalResult result = EvaluateFeatures(set.sequences, options);
  for (const TypeSummary& s : result.types) {
    EXPECT_EQ(s.pairs, 3);
    EXPECT_GT(s.repeatability, 0.6) << s.type;
    EXPECT_GT(s.homography_accuracy, 0.99) << s.type;
    for (const PairRecord& r : s.records) EXPECT_LT(r.metrics.corner_error_px, 1.0) << s.type;
  }
  EXPECT_EQ(ToJson(result)["layout"], "static");
  EXPECT_NE(ToMarkdown(result).find("| orb | webcam | 1-4 |"), std::string::npos);
}

TEST(SequenceEvalTest, StaticImagesOfAnotherSizeAreNamed) {
  const fs::path dir = fs::path(DUSKMAP_BINARY_DIR) / "features_eval_static_sizes";
  fs::remove_all(dir);
  testing::WriteStaticScene(dir, 2);
  cv::imwrite((dir / "img3.png").string(), testing::TexturedImage(200, 240, 3));
  const SequenceSet set = FindImageSequences(dir.string(), std::nullopt);
  FeatureEvalOptions options;
  options.types = {"orb"};
  EXPECT_EQ(testing::ErrorOf([&] { EvaluateFeatures(set.sequences, options); }),
            (dir / "img3.png").string() + ": 200x240, but img1.png is 320x240 (a fixed camera's images have one size)");
}

TEST(SequenceEvalTest, MissingDataIsAClearInputError) {
  EXPECT_THROW(FindImageSequences("/nonexistent/sequence", std::nullopt), InputError);
  const fs::path empty = fs::path(DUSKMAP_BINARY_DIR) / "features_eval_empty";
  fs::create_directories(empty);
  EXPECT_THROW(FindImageSequences(empty.string(), std::nullopt), InputError);
  const fs::path lonely = fs::path(DUSKMAP_BINARY_DIR) / "features_eval_lonely";
  fs::create_directories(lonely);
  cv::imwrite((lonely / "img1.png").string(), cv::Mat(20, 20, CV_8UC1, cv::Scalar(9)));
  EXPECT_NE(testing::ErrorOf([&] { ReadImageSequence(lonely.string(), SequenceLayout::kHomography); })
                .find("H1to2p"),
            std::string::npos);
  EXPECT_NE(testing::ErrorOf([&] { FindImageSequences(lonely.string(), std::nullopt); })
                .find("a fixed camera's sequence needs two or more"),
            std::string::npos);
}

// The own descriptors on the real oxford-leuven light-change sequence behave
// as their papers report: usable matches down to the darkest image, with a
// matching score that falls as the light does.
TEST(SequenceEvalTest, OxfordLeuvenLightChange) {
  if (!fs::exists(testing::LeuvenDir())) {
    GTEST_SKIP() << testing::LeuvenDir() << " absent (../shared is not part of the project)";
  }
  FeatureEvalOptions options;
  options.types = {"surf", "brief", "daisy", "freak"};
  const FeatureEvalResult result =
      EvaluateFeatures(FindImageSequences(testing::LeuvenDir(), std::nullopt).sequences, options);
  double surf_darkest = 0.0, daisy_darkest = 0.0;
  for (const TypeSummary& s : result.types) {
    ASSERT_EQ(s.pairs, 5) << s.type;
    const PairMetrics& brightest = s.records.front().metrics;  // img1 -> img2
    const PairMetrics& darkest = s.records.back().metrics;     // img1 -> img6
    EXPECT_GT(brightest.matching_score, darkest.matching_score) << s.type;
    if (s.type == "surf") surf_darkest = darkest.matching_score;
    if (s.type == "daisy") {
      // Raw histograms, as the reference's DAISY leaves them, shrink with the
      // contrast: the darkest image's descriptors lie nearer other keypoints'.
      daisy_darkest = darkest.matching_score;
      continue;
    }
    EXPECT_GT(darkest.matching_score, 0.2) << s.type;
    EXPECT_GT(s.homography_accuracy, 0.79) << s.type;
    EXPECT_GT(s.mma[1], 0.6) << s.type;
  }
  EXPECT_LT(daisy_darkest, 0.5 * surf_darkest);
}

}  // namespace
}  // namespace duskmap
