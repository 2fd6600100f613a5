// The real-image illumination benchmark behind `duskmap features eval`:
// image sequences (image_sequence.h: the Oxford/HPatches homography layout,
// or a fixed camera's images with the identity), every selected pair
// evaluated per feature type with homography_metrics.h, averaged per type.
#pragma once

#include <array>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

#include "slam/features/eval/homography_metrics.h"
#include "slam/features/eval/image_sequence.h"
#include "slam/features/feature_options.h"

namespace duskmap {

struct FeatureEvalOptions {
  std::vector<std::string> types = BuiltInFeatureTypeNames();
  FeatureOptions features;  // shared options; `type` is replaced per entry of `types`
  HomographyMetricsOptions metrics;
  void Check() const;
};

struct PairRecord {
  std::string sequence;
  int reference_index = 0;  // the pair's first image (N of imgN)
  int target_index = 0;     // its second
  std::string reference_image;  // file names
  std::string target_image;
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
  SequenceLayout layout = SequenceLayout::kHomography;
  std::vector<std::string> sequences;
  FeatureEvalOptions options;
  std::vector<TypeSummary> types;
};

// Each image of a sequence's pairs is read and extracted once per type. A
// static pair whose images differ in size is an InputError naming both.
FeatureEvalResult EvaluateFeatures(const std::vector<ImageSequence>& sequences,
                                   const FeatureEvalOptions& options);

nlohmann::json ToJson(const FeatureEvalResult& result);
// One row per type: keypoints/image, repeatability, matching score, MMA@1/3/5,
// homography accuracy, ms/image, descriptor bytes; then one row per type and
// pair (keypoints, matches, the same scores, corner error).
std::string ToMarkdown(const FeatureEvalResult& result);

}  // namespace duskmap
