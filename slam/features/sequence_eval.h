// The real-image illumination benchmark behind `duskmap features eval`:
// sequences in the Oxford/HPatches layout (img1 = reference, img2..imgN,
// H1toNp homographies reference -> target), every pair evaluated per feature
// type with homography_metrics.h, averaged per type.
#pragma once

#include <array>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

#include "slam/features/feature_options.h"
#include "slam/features/homography_metrics.h"

namespace duskmap {

struct HomographySequence {
  std::string name;
  std::string reference_path;
  std::vector<std::string> target_paths;
  std::vector<cv::Matx33d> target_from_reference;  // H1toNp, one per target
};

// Reads one sequence folder (img1.{ppm,png,jpg} and every imgN with an
// H1toNp); throws InputError when the reference or all targets are missing.
HomographySequence ReadHomographySequence(const std::string& directory);

// `root` itself when it is a sequence, else each sub-folder that is one
// (sorted by name); throws InputError when none is found.
std::vector<HomographySequence> FindHomographySequences(const std::string& root);

struct FeatureEvalOptions {
  std::vector<std::string> types = {"surf", "sift", "brief", "brisk", "kaze",
                                    "daisy", "orb", "akaze", "freak"};
  FeatureOptions features;  // shared options; `type` is replaced per entry of `types`
  HomographyMetricsOptions metrics;
  void Check() const;
};

struct PairRecord {
  std::string sequence;
  int target_index = 0;  // N of imgN
  PairMetrics metrics;
};

struct TypeSummary {
  std::string type;
  int pairs = 0;
  double keypoints_per_image = 0.0;
  double repeatability = 0.0;
  double matching_score = 0.0;
  std::array<double, 3> mma = {0.0, 0.0, 0.0};
  double homography_accuracy = 0.0;  // fraction of pairs with corner error < threshold
  double extraction_ms = 0.0;        // mean per image
  int descriptor_bytes = 0;
  std::vector<PairRecord> records;
};

struct FeatureEvalResult {
  std::vector<std::string> sequences;
  FeatureEvalOptions options;
  std::vector<TypeSummary> types;
};

FeatureEvalResult EvaluateFeatures(const std::vector<HomographySequence>& sequences,
                                   const FeatureEvalOptions& options);

nlohmann::json ToJson(const FeatureEvalResult& result);
// One row per type: keypoints/image, repeatability, matching score, MMA@1/3/5,
// homography accuracy, ms/image, descriptor bytes.
std::string ToMarkdown(const FeatureEvalResult& result);

}  // namespace duskmap
