#include "slam/features/superglue.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "slam/features/feature_options_json.h"
#include "slam/features/matcher_options.h"
#include "slam/features/superpoint.h"
#include "tests/features/superglue_test_models.h"
#include "tests/features/test_images.h"

namespace duskmap {
namespace {

namespace fs = std::filesystem;
using testing::MakeSuperGlueModel;
using testing::MakeSuperPointModel;

// A log assignment from probabilities (log taken here); rows and columns
// beyond the given ones are the dustbins.
cv::Mat LogOf(const cv::Mat& probabilities) {
  cv::Mat log_p;
  cv::log(probabilities, log_p);
  return log_p;
}

TEST(SuperGlueDecodingTest, MutualBestPairsAboveThresholdAreMatched) {
  // 3 x 3 inner block + dustbins; the diagonal dominates.
  const cv::Mat p = (cv::Mat_<float>(4, 4) << 0.90f, 0.02f, 0.03f, 0.05f,  //
                     0.01f, 0.60f, 0.09f, 0.30f,                           //
                     0.04f, 0.08f, 0.50f, 0.38f,                           //
                     0.05f, 0.30f, 0.38f, 1.00f);
  const std::vector<cv::DMatch> matches = DecodeSuperGlueAssignment(LogOf(p), 0.2);
  ASSERT_EQ(matches.size(), 3u);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(matches[i].queryIdx, i);
    EXPECT_EQ(matches[i].trainIdx, i);
    EXPECT_NEAR(matches[i].distance, 1.0f - p.at<float>(i, i), 1e-6f);
  }
}

TEST(SuperGlueDecodingTest, NonMutualBestIsRejected) {
  // Row 0 prefers column 0, but column 0 prefers row 1: only (1, 0) survives.
  const cv::Mat p = (cv::Mat_<float>(3, 3) << 0.40f, 0.30f, 0.30f,  //
                     0.70f, 0.25f, 0.05f,                           //
                     0.30f, 0.45f, 1.00f);
  const std::vector<cv::DMatch> matches = DecodeSuperGlueAssignment(LogOf(p), 0.2);
  ASSERT_EQ(matches.size(), 1u);
  EXPECT_EQ(matches[0].queryIdx, 1);
  EXPECT_EQ(matches[0].trainIdx, 0);
  // Row 0's best column (0) is taken by row 1; the decoder does not fall back
  // to row 0's second choice (column 1), as in the reference.
}

TEST(SuperGlueDecodingTest, DustbinWinsLeavesTheRowUnmatched) {
  // Row 0 puts most of its mass in the dustbin: its best real column (0) is
  // mutual but below the threshold. Column 1's dustbin entry is larger than
  // any real entry, yet dustbins are never match candidates: row 1 and
  // column 1 still match (0.3 > 0.2).
  const cv::Mat p = (cv::Mat_<float>(3, 3) << 0.15f, 0.05f, 0.80f,  //
                     0.05f, 0.30f, 0.65f,                           //
                     0.80f, 0.65f, 1.00f);
  const std::vector<cv::DMatch> matches = DecodeSuperGlueAssignment(LogOf(p), 0.2);
  ASSERT_EQ(matches.size(), 1u);
  EXPECT_EQ(matches[0].queryIdx, 1);
  EXPECT_EQ(matches[0].trainIdx, 1);
  for (const cv::DMatch& m : matches) {
    EXPECT_LT(m.queryIdx, 2);
    EXPECT_LT(m.trainIdx, 2);
  }
}

TEST(SuperGlueDecodingTest, ThresholdIsOnExpScoreAndStrict) {
  const cv::Mat p = (cv::Mat_<float>(3, 3) << 0.25f, 0.01f, 0.74f,  //
                     0.01f, 0.19f, 0.80f,                           //
                     0.74f, 0.80f, 1.00f);
  const cv::Mat log_p = LogOf(p);
  std::vector<cv::DMatch> matches = DecodeSuperGlueAssignment(log_p, 0.2);
  ASSERT_EQ(matches.size(), 1u);  // 0.25 passes, 0.19 does not
  EXPECT_EQ(matches[0].queryIdx, 0);
  EXPECT_TRUE(DecodeSuperGlueAssignment(log_p, 0.25).empty());  // strict ">"
  EXPECT_EQ(DecodeSuperGlueAssignment(log_p, 0.0).size(), 2u);
  EXPECT_EQ(DecodeSuperGlueAssignment(log_p, 0.18).size(), 2u);
}

TEST(SuperGlueDecodingTest, TiesAndNonFiniteEntries) {
  cv::Mat log_p(3, 4, CV_32F, cv::Scalar(std::log(0.1f)));
  log_p.at<float>(0, 0) = log_p.at<float>(0, 1) = std::log(0.45f);  // tie: lowest column
  log_p.at<float>(1, 1) = std::nanf("");                            // never wins
  log_p.at<float>(1, 2) = std::log(0.5f);
  const std::vector<cv::DMatch> matches = DecodeSuperGlueAssignment(log_p, 0.2);
  ASSERT_EQ(matches.size(), 2u);
  EXPECT_EQ(matches[0].trainIdx, 0);
  EXPECT_EQ(matches[1].queryIdx, 1);
  EXPECT_EQ(matches[1].trainIdx, 2);
  // No real rows or columns: nothing to match.
  EXPECT_TRUE(DecodeSuperGlueAssignment(cv::Mat(1, 5, CV_32F, cv::Scalar(0.0f)), 0.2).empty());
  EXPECT_TRUE(DecodeSuperGlueAssignment(cv::Mat(5, 1, CV_32F, cv::Scalar(0.0f)), 0.2).empty());
}

TEST(SuperGlueInputTest, KeypointsNormalisedByTheLargerImageSide) {
  const std::vector<cv::KeyPoint> kps = {cv::KeyPoint(320.0f, 240.0f, 8.0f),
                                         cv::KeyPoint(0.0f, 0.0f, 8.0f),
                                         cv::KeyPoint(640.0f, 480.0f, 8.0f)};
  const cv::Mat blob = NormalizeSuperGlueKeypoints(kps, cv::Size(640, 480));
  ASSERT_EQ(blob.dims, 3);
  EXPECT_EQ(blob.size[0], 1);
  EXPECT_EQ(blob.size[1], 3);
  EXPECT_EQ(blob.size[2], 2);
  const float* p = blob.ptr<float>();
  EXPECT_FLOAT_EQ(p[0], 0.0f);
  EXPECT_FLOAT_EQ(p[1], 0.0f);
  EXPECT_FLOAT_EQ(p[2], -320.0f / 448.0f);  // 0.7 * 640 = 448
  EXPECT_FLOAT_EQ(p[3], -240.0f / 448.0f);
  EXPECT_FLOAT_EQ(p[4], 320.0f / 448.0f);
  EXPECT_FLOAT_EQ(p[5], 240.0f / 448.0f);
}

TEST(SuperGlueInputTest, LogMarginalsAreTheReferenceOnesTimesMPlusN) {
  cv::Mat log_mu, log_nu;
  SuperGlueLogMarginals(3, 5, &log_mu, &log_nu);
  ASSERT_EQ(log_mu.total(), 4u);
  ASSERT_EQ(log_nu.total(), 6u);
  EXPECT_EQ(log_mu.size[1], 4);
  EXPECT_EQ(log_mu.size[2], 1);
  // Reference: mu = [1/8, 1/8, 1/8, 5/8]; times 8 -> [1, 1, 1, 5].
  const float* mu = log_mu.ptr<float>();
  const float* nu = log_nu.ptr<float>();
  for (int i = 0; i < 3; ++i) EXPECT_FLOAT_EQ(mu[i], 0.0f);
  EXPECT_FLOAT_EQ(mu[3], std::log(5.0f));
  for (int j = 0; j < 5; ++j) EXPECT_FLOAT_EQ(nu[j], 0.0f);
  EXPECT_FLOAT_EQ(nu[5], std::log(3.0f));
}

TEST(SuperGlueOptionsTest, CheckAndJson) {
  SuperGlueOptions bad;
  bad.match_threshold = 1.0;
  EXPECT_THROW(bad.Check(), ConfigError);
  MatcherOptions nndr;
  EXPECT_EQ(CreateFeatureMatcher(nndr), nullptr);  // registration builds its NNDR matcher
  JsonFields fields(nlohmann::json::parse(R"({"type": "superglue",
      "superglue": {"model_path": "x.onnx", "match_threshold": 0.3}})"),
                    "test");
  const MatcherOptions read = ReadJsonOptions<MatcherOptions>(fields);
  EXPECT_EQ(read.type, "superglue");
  EXPECT_EQ(read.superglue.model_path, "x.onnx");
  EXPECT_DOUBLE_EQ(read.superglue.match_threshold, 0.3);
  EXPECT_EQ(ToJsonObject(read)["superglue"]["match_threshold"], 0.3);
  JsonFields typo(nlohmann::json::parse(R"({"type": "superglue", "superglue": {"treshold": 0.3}})"),
                  "test");
  EXPECT_THROW(ReadJsonOptions<MatcherOptions>(typo), ConfigError);
  JsonFields unknown(nlohmann::json::parse(R"({"type": "lightglue"})"), "test");
  EXPECT_THROW(ReadJsonOptions<MatcherOptions>(unknown), ConfigError);
}

// The error message of constructing a matcher from `path`, or "" if none.
std::string LoadError(const std::string& path) {
  SuperGlueOptions options;
  options.model_path = path;
  try {
    SuperGlueMatcher matcher(options);
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.find('\n'), std::string::npos) << "one line: " << what;
    return what;
  }
  return "";
}

TEST(SuperGlueTest, MissingOrWrongModelIsAClearOneLineInputError) {
  EXPECT_NE(LoadError("").find("no ONNX model given"), std::string::npos);
  const std::string missing = std::string(DUSKMAP_BINARY_DIR) + "/no_such_superglue.onnx";
  EXPECT_NE(LoadError(missing).find("no_such_superglue.onnx: SuperGlue ONNX model not found"),
            std::string::npos);
  const std::string junk = std::string(DUSKMAP_BINARY_DIR) + "/superglue_junk.onnx";
  std::ofstream(junk) << "this is not an ONNX file";
  EXPECT_NE(LoadError(junk).find("superglue_junk.onnx: not a readable ONNX model"),
            std::string::npos);

  const std::string wrong = MakeSuperGlueModel("superglue_wrong_output.onnx", "--wrong-output --layers 2");
  if (wrong.empty()) GTEST_SKIP() << "python3-onnx unavailable: cannot write the test models";
  const std::string wrong_error = LoadError(wrong);
  EXPECT_NE(wrong_error.find("not a SuperGlue model (output scores must be 1x4x3"),
            std::string::npos)
      << wrong_error;
  const std::string superpoint = MakeSuperPointModel("superglue_tests_superpoint_random.onnx");
  ASSERT_FALSE(superpoint.empty());
  const std::string superpoint_error = LoadError(superpoint);
  EXPECT_NE(superpoint_error.find("superpoint_random.onnx: not a SuperGlue model"), std::string::npos)
      << superpoint_error;
}

// Features with random unit 256-D descriptors at random pixels.
FrameFeatures RandomFeatures(int count, const cv::Size& image, uint64_t seed) {
  cv::RNG rng(seed);
  FrameFeatures f;
  f.descriptors.create(count, 256, CV_32F);
  rng.fill(f.descriptors, cv::RNG::NORMAL, 0.0, 1.0);
  for (int i = 0; i < count; ++i) {
    cv::Mat row = f.descriptors.row(i);
    row /= cv::norm(row);
    f.keypoints.emplace_back(cv::Point2f(rng.uniform(0.0f, float(image.width)),
                                         rng.uniform(0.0f, float(image.height))),
                             8.0f, -1.0f, rng.uniform(0.01f, 1.0f));
  }
  return f;
}

TEST(SuperGlueTest, WrongDescriptorsOrSizesAreClearInputErrors) {
  const std::string model = MakeSuperGlueModel("superglue_random.onnx");
  if (model.empty()) GTEST_SKIP() << "python3-onnx unavailable: cannot write the test model";
  SuperGlueOptions options;
  options.model_path = model;
  const SuperGlueMatcher matcher(options);
  const cv::Size size(64, 48);
  const FrameFeatures good = RandomFeatures(5, size, 1);
  FrameFeatures sift_like = RandomFeatures(5, size, 2);
  sift_like.descriptors = sift_like.descriptors.colRange(0, 128).clone();
  EXPECT_THROW(matcher.Match(good, size, sift_like, size), InputError);
  FrameFeatures binary = good;
  binary.descriptors = cv::Mat(5, 32, CV_8U, cv::Scalar(7));
  EXPECT_THROW(matcher.Match(binary, size, good, size), InputError);
  FrameFeatures short_rows = good;
  short_rows.descriptors = good.descriptors.rowRange(0, 4).clone();
  EXPECT_THROW(matcher.Match(good, size, short_rows, size), InputError);
  EXPECT_THROW(matcher.Match(good, cv::Size(), good, size), InputError);
  EXPECT_TRUE(matcher.Match(good, size, FrameFeatures(), size).empty());
  EXPECT_TRUE(matcher.Match(FrameFeatures(), size, good, size).empty());
}

// Reads the script's test vector: index.txt lists "name d0 d1 ..." per raw
// little-endian float32 file and the two image sizes.
struct TestVector {
  std::map<std::string, cv::Mat> arrays;  // 2-D (or 1-row) CV_32F
  cv::Size image0, image1;
};

TestVector ReadTestVector(const std::string& dir) {
  TestVector tv;
  std::ifstream index(dir + "/index.txt");
  std::string line;
  while (std::getline(index, line)) {
    std::istringstream in(line);
    std::string name;
    int a = 0, b = 1;
    in >> name >> a;
    if (!(in >> b)) b = 1;
    if (name == "image0" || name == "image1") {
      (name == "image0" ? tv.image0 : tv.image1) = cv::Size(a, b);
      continue;
    }
    cv::Mat m(a, b, CV_32F);
    std::ifstream data(dir + "/" + name + ".f32", std::ios::binary);
    data.read(reinterpret_cast<char*>(m.data), static_cast<std::streamsize>(m.total() * 4));
    EXPECT_TRUE(data.good()) << name;
    tv.arrays[name] = m;
  }
  return tv;
}

FrameFeatures FromTestVector(const TestVector& tv, int side) {
  const std::string s = std::to_string(side);
  const cv::Mat& pixels = tv.arrays.at("pixels" + s);
  const cv::Mat& scores = tv.arrays.at("scores" + s);
  FrameFeatures f;
  for (int i = 0; i < pixels.rows; ++i) {
    f.keypoints.emplace_back(cv::Point2f(pixels.at<float>(i, 0), pixels.at<float>(i, 1)), 8.0f,
                             -1.0f, scores.at<float>(i, 0));
  }
  f.descriptors = tv.arrays.at("descriptors" + s).clone();
  return f;
}

TEST(SuperGlueTest, GraphThroughOpenCvMatchesTheReferenceEquations) {
  // The script computes the expected log assignment with a float64 numpy
  // transcription of the reference (einsum attention, logsumexp Sinkhorn);
  // here the same pixels, scores and descriptors go through duskmap's input
  // preparation and OpenCV's DNN module.
  const std::string dir = std::string(DUSKMAP_BINARY_DIR) + "/superglue_test_vector";
  const std::string model = MakeSuperGlueModel("superglue_random.onnx", "", dir);
  if (model.empty()) GTEST_SKIP() << "python3-onnx unavailable: cannot write the test model";
  const TestVector tv = ReadTestVector(dir);
  ASSERT_EQ(tv.arrays.count("expected"), 1u);
  SuperGlueOptions options;
  options.model_path = model;
  const SuperGlueMatcher matcher(options);
  const FrameFeatures f0 = FromTestVector(tv, 0), f1 = FromTestVector(tv, 1);
  const cv::Mat got = matcher.LogAssignment(f0, tv.image0, f1, tv.image1);
  const cv::Mat& expected = tv.arrays.at("expected");
  ASSERT_EQ(got.size(), expected.size());
  EXPECT_LT(cv::norm(got, expected, cv::NORM_INF), 1e-4);
  // Sinkhorn output: every real row sums (in probability) to 1, the dustbin
  // row to N, as the reference's marginals times M + N.
  cv::Mat p;
  cv::exp(got, p);
  for (int i = 0; i < static_cast<int>(f0.size()); ++i) EXPECT_NEAR(cv::sum(p.row(i))[0], 1.0, 1e-3);
}

TEST(SuperGlueTest, RandomWeightModelOnRealImagesGivesAMutualThresholdedMatchSet) {
  const std::string dir = testing::LeuvenDir();
  const cv::Mat img1 = cv::imread(dir + "/img1.ppm"), img2 = cv::imread(dir + "/img2.ppm");
  if (img1.empty() || img2.empty()) GTEST_SKIP() << dir << " absent: real-image test skipped";
  const std::string superpoint = MakeSuperPointModel("superglue_tests_superpoint_random.onnx");
  const std::string superglue = MakeSuperGlueModel("superglue_random.onnx");
  if (superpoint.empty() || superglue.empty()) {
    GTEST_SKIP() << "python3-onnx unavailable: cannot write the test models";
  }
  SuperPointOptions sp;
  sp.model_path = superpoint;
  const std::unique_ptr<FeatureExtractor> extractor = CreateSuperPointExtractor(sp, 300);
  const FrameFeatures f1 = extractor->Extract(img1), f2 = extractor->Extract(img2);
  ASSERT_GT(f1.size(), 50u);
  ASSERT_GT(f2.size(), 50u);
  SuperGlueOptions options;
  options.model_path = superglue;
  const SuperGlueMatcher matcher(options);
  const cv::Mat log_p = matcher.LogAssignment(f1, img1.size(), f2, img2.size());
  ASSERT_EQ(log_p.rows, static_cast<int>(f1.size()) + 1);
  ASSERT_EQ(log_p.cols, static_cast<int>(f2.size()) + 1);
  ASSERT_TRUE(cv::checkRange(log_p));
  // Mutual arg-max pairs of the inner block, recomputed independently.
  const cv::Mat inner = log_p(cv::Rect(0, 0, log_p.cols - 1, log_p.rows - 1));
  std::map<std::pair<int, int>, double> mutual;  // -> exp(score)
  for (int i = 0; i < inner.rows; ++i) {
    cv::Point best_j, best_i;
    double row_max;
    cv::minMaxLoc(inner.row(i), nullptr, &row_max, nullptr, &best_j);
    cv::minMaxLoc(inner.col(best_j.x), nullptr, nullptr, nullptr, &best_i);
    if (best_i.y == i) mutual[{i, best_j.x}] = std::exp(row_max);
  }
  ASSERT_GT(mutual.size(), 10u);
  // Random SuperPoint descriptors are all alike (cosines about 0.95), so the
  // random SuperGlue spreads its mass and no pair reaches the reference
  // threshold 0.2; the median confidence of the mutual pairs as threshold
  // makes the thresholding visible too.
  std::vector<double> confidences;
  for (const auto& [pair, p] : mutual) confidences.push_back(p);
  std::nth_element(confidences.begin(), confidences.begin() + confidences.size() / 2,
                   confidences.end());
  for (const double threshold : {0.2, confidences[confidences.size() / 2]}) {
    SCOPED_TRACE("threshold " + std::to_string(threshold));
    options.match_threshold = threshold;
    const SuperGlueMatcher thresholded(options);
    const std::vector<cv::DMatch> matches = thresholded.Match(f1, img1.size(), f2, img2.size());
    std::set<std::pair<int, int>> expected, got;
    for (const auto& [pair, p] : mutual) {
      if (p > threshold) expected.insert(pair);
    }
    std::set<int> used_train;
    for (const cv::DMatch& m : matches) {
      got.insert({m.queryIdx, m.trainIdx});
      EXPECT_TRUE(used_train.insert(m.trainIdx).second) << "train feature matched twice";
      EXPECT_LT(m.distance, 1.0 - threshold);
      EXPECT_NEAR(m.distance, 1.0 - std::exp(inner.at<float>(m.queryIdx, m.trainIdx)), 1e-5);
    }
    EXPECT_EQ(got, expected);
    if (threshold != 0.2) {
      EXPECT_GT(got.size(), 0u);
      EXPECT_LT(got.size(), mutual.size());
    }
    std::cout << "[ info ] leuven 1-2, " << f1.size() << "x" << f2.size()
              << " random-weight SuperPoint features, threshold " << threshold << ": "
              << matches.size() << " of " << mutual.size() << " mutual pairs\n";
  }
}

}  // namespace
}  // namespace duskmap
