// The homography-free benchmark behind `duskmap features eval` on image pairs
// of 3D scenes in the WxBS layout: a folder per pair with 01.* and 02.* and
// corrs.txt, whose rows "x1 y1 x2 y2" are correspondences clicked by hand
// (pixels, OpenCV's convention). Per pair and feature type: ratio-test
// matches, a fundamental matrix fitted by RANSAC (OpenCV's USAC MAGSAC++),
// and the median symmetric epipolar distance of the ground-truth
// correspondences under it; a pair is solved at 2, 5 and 10 px when that
// median is at most the threshold. Pairs sit directly under the data root or
// one level deeper, in category folders (WxBS: WGABS, WGALBS, ...).
#pragma once

#include <array>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

#include "slam/features/eval/eval_pairs.h"
#include "slam/features/feature_options.h"

namespace duskmap {

struct CorrespondencePair {
  std::string name;      // relative to the data root: "WGALBS/kremlin" ("kremlin" at the top)
  std::string category;  // the category folder, "" for pairs directly under the root
  std::string first_path;
  std::string second_path;
  std::vector<cv::Vec4d> correspondences;  // x1 y1 x2 y2, pixels
};

// Whether `directory` is meant as a pair folder: it holds corrs.txt, or 01.*
// or 02.* and no other image (a fixed camera's sequence may be named 01.png,
// 02.png, 03.png, ...: image_sequence.h).
bool IsCorrespondencePairFolder(const std::string& directory);
// Reads one pair folder; throws InputError naming the missing file (01.*,
// 02.* or corrs.txt), or corrs.txt (and its line) when a row is not four
// finite numbers or it has no row.
CorrespondencePair ReadCorrespondencePair(const std::string& directory, const std::string& name,
                                          const std::string& category);
// `root` itself when it is a pair folder, else its pair sub-folders and the
// pair folders of its category sub-folders (sorted by name); empty when
// none. A pair folder missing a file is an error, never skipped.
std::vector<CorrespondencePair> FindCorrespondencePairs(const std::string& root);

// Keeps the pairs named by `selectors` ("WGALBS/kremlin": a pair's name), in
// the selectors' order; ConfigError naming the selector's origin when no
// pair has that name.
std::vector<CorrespondencePair> SelectCorrespondencePairs(const std::vector<CorrespondencePair>& pairs,
                                                          const std::vector<PairSelector>& selectors);

// The symmetric epipolar distance of x1 <-> x2 under F (x2^T F x1 = 0): the
// mean of x2's distance to the line F x1 and x1's to F^T x2, pixels.
double SymmetricEpipolarDistancePx(const cv::Matx33d& f, const cv::Point2d& x1, const cv::Point2d& x2);

struct EpipolarEvalOptions {
  std::vector<std::string> types = BuiltInFeatureTypeNames();
  FeatureOptions features;            // shared options; `type` is replaced per entry of `types`
  double float_ratio = 0.8;           // Lowe's ratio test, L2
  double binary_ratio = 0.8;          // the same over Hamming distances
  double ransac_threshold_px = 1.0;   // MAGSAC++'s threshold
  double ransac_confidence = 0.9999;
  int ransac_max_iterations = 10000;
  std::array<double, 3> solved_px = {2.0, 5.0, 10.0};
  void Check() const;
};

struct EpipolarPairRecord {
  std::string pair;
  std::string category;
  int keypoints_first = 0;
  int keypoints_second = 0;
  int matches = 0;            // after the ratio test
  int inliers = 0;            // of the fitted F
  bool estimated = false;     // false: fewer than 8 matches or RANSAC failed
  double median_error_px = 0.0;  // of the ground-truth correspondences; infinity without F
};

struct EpipolarTypeSummary {
  std::string type;
  int pairs = 0;
  std::array<int, 3> solved = {0, 0, 0};  // at options.solved_px
  std::map<std::string, std::array<int, 3>> solved_by_category;
  std::map<std::string, int> pairs_by_category;
  double median_error_px = 0.0;  // over pairs (infinity counts as unsolved)
  double extraction_ms = 0.0;    // mean per image
  std::vector<EpipolarPairRecord> records;
};

struct EpipolarEvalResult {
  std::vector<std::string> pairs;
  EpipolarEvalOptions options;
  std::vector<EpipolarTypeSummary> types;
};

// Extracts with FeatureExtractor::ExtractFrame (an imported h5 type reads
// group "<pair name>/01.<ext>"). Throws InputError naming corrs.txt when a
// correspondence lies outside its image.
EpipolarEvalResult EvaluateOnCorrespondencePairs(const std::vector<CorrespondencePair>& pairs,
                                                 const EpipolarEvalOptions& options);

nlohmann::json ToJson(const EpipolarEvalResult& result);
// One row per type: pairs solved at 2/5/10 px, median error, ms/image; then
// solved counts per category; then one row per type and pair.
std::string ToMarkdown(const EpipolarEvalResult& result);

}  // namespace duskmap
