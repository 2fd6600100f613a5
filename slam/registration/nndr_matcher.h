// Nearest-neighbour distance ratio matching (Lowe's test) of query features
// against a map node's features, with the reference's uniqueness filter
// (spec 6.2): a map feature matched by more than one query feature is dropped
// together with all those matches.
//
// Distances: squared L2 for float descriptors, Hamming or byte L1 for binary
// ones (NndrMatcherOptions::binary_distance). The
// ratio is applied to those distances as the reference does (Vis/CorNNDR on
// squared L2), so a float ratio of 0.6 is 0.775 on plain Euclidean distance.
// The test is strict (d1 < ratio * d2), so exact ties (d2 == 0) never match.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "slam/features/binary_distance.h"
#include "slam/features/feature_matcher.h"
#include "slam/features/frame_features.h"

namespace duskmap {

enum class NndrSearch {
  kAuto,        // KD-tree for float descriptors when the map node is large, else brute force
  kBruteForce,  // exact 2-NN
  kKdTree,      // FLANN randomized KD-trees (float descriptors only)
};

struct NndrMatcherOptions {
  double float_ratio = 0.6;   // on squared L2 distance (paper's runs with float descriptors)
  double binary_ratio = 0.8;  // on the binary distance (paper's runs with binary descriptors)
  // How binary descriptors are compared (binary_distance.h): Hamming, or the
  // L1 of the byte values as the reference's KD-tree matching does with
  // Kp/ByteToFloat (the paper's runs). Both searches are exact here.
  BinaryDistance binary_distance = BinaryDistance::kHamming;
  NndrSearch search = NndrSearch::kAuto;
  int kd_min_train_size = 5000;  // kAuto uses the KD-tree from this many map features on
  int kd_trees = 4;             // FLANN randomized trees (reference: 4)
  int kd_checks = 32;           // FLANN leaf checks per query (reference: 32)
  bool unique = true;           // the uniqueness filter of spec 6.2
  uint64_t random_seed = 0;     // seeds the KD-tree construction

  void Check() const;
  double RatioFor(DescriptorKind kind) const {
    return kind == DescriptorKind::kFloat ? float_ratio : binary_ratio;
  }
};

// The two nearest neighbours of one query descriptor; index -1 when absent.
struct TwoNearest {
  int best = -1;
  int second = -1;
  double best_distance = 0.0;    // squared L2, Hamming or byte L1
  double second_distance = 0.0;  // squared L2, Hamming or byte L1
};

// Distance between two descriptor rows as the guess-window ratio test uses
// it: squared L2, or Hamming for binary rows (the reference's BFMatcher,
// whatever Kp/ByteToFloat says).
double DescriptorDistance(const cv::Mat& a, int row_a, const cv::Mat& b, int row_b,
                          DescriptorKind kind);

class NndrMatcher : public FeatureMatcher {
 public:
  explicit NndrMatcher(NndrMatcherOptions options = {});
  std::string name() const override { return "nndr"; }
  // Throws InputError when the descriptors of query and train differ in kind,
  // type or width, or do not have one row per keypoint.
  std::vector<cv::DMatch> Match(const FrameFeatures& query, const cv::Size& query_image,
                                const FrameFeatures& train,
                                const cv::Size& train_image) const override;
  const NndrMatcherOptions& options() const { return options_; }

 private:
  NndrMatcherOptions options_;
};

// Throws InputError naming `what` when the features are internally
// inconsistent (descriptor rows vs keypoints, type vs kind, 3D point count).
void CheckFeatures(const FrameFeatures& features, const char* what);
// Throws InputError when the two descriptor sets cannot be compared.
void CheckComparable(const FrameFeatures& a, const FrameFeatures& b);

}  // namespace duskmap
