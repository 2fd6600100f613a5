// Generic RANSAC over an estimator concept (after COLMAP optim/ransac.h and
// PoseLib robust/ransac_impl.h). The estimator provides:
//
//   using Model = ...;
//   static constexpr int kMinSampleSize = ...;
//   // Fills *models with every model consistent with the minimal sample
//   // (indices into the data); may leave it empty for a degenerate sample.
//   void Estimate(const std::vector<int>& sample, std::vector<Model>* models) const;
//   // One non-negative residual per datum (e.g. reprojection error in px);
//   // +inf for data the model cannot explain (behind the camera).
//   void Residuals(const Model& model, std::vector<double>* residuals) const;
//   // Refits the model on an inlier set (>= kMinSampleSize); false on failure.
//   bool Refine(const std::vector<int>& inliers, Model* model) const;
//
// Models are scored by inlier count, ties broken by the truncated squared
// residual sum (MSAC). The number of trials adapts to the best inlier ratio:
// N = log(1 - confidence) / log(1 - w^s). Sampling is seeded, so the same
// data and options give the same result.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "slam/core/check.h"
#include "slam/core/random.h"

namespace duskmap {

struct RansacOptions {
  double max_residual = 4.0;  // inlier threshold, in the estimator's residual units
  double confidence = 0.99;   // wanted probability of drawing one all-inlier sample
  int min_trials = 0;         // trials run even when the adaptive count is lower
  int max_trials = 300;       // hard cap on trials (reference Vis/Iterations)
  int refine_rounds = 2;      // refit-on-inliers / re-select rounds after sampling
  uint64_t random_seed = 0;   // seeds the sample generator

  void Check() const {
    SLAM_THROW_IF_NOT(ConfigError, max_residual > 0.0 && std::isfinite(max_residual))
        << "RansacOptions.max_residual: must be finite and > 0, got " << max_residual;
    SLAM_THROW_IF_NOT(ConfigError, confidence > 0.0 && confidence < 1.0)
        << "RansacOptions.confidence: must be in (0, 1), got " << confidence;
    SLAM_THROW_IF_NOT(ConfigError, min_trials >= 0)
        << "RansacOptions.min_trials: must be >= 0, got " << min_trials;
    SLAM_THROW_IF_NOT(ConfigError, max_trials >= 1 && max_trials >= min_trials)
        << "RansacOptions.max_trials: must be >= 1 and >= min_trials, got " << max_trials;
    SLAM_THROW_IF_NOT(ConfigError, refine_rounds >= 0)
        << "RansacOptions.refine_rounds: must be >= 0, got " << refine_rounds;
  }
};

template <typename Model>
struct RansacReport {
  bool success = false;      // a model with >= kMinSampleSize inliers was found
  Model model{};             // the best (refined) model when success
  std::vector<int> inliers;  // indices of the data within max_residual of model
  int num_trials = 0;        // minimal samples drawn
};

namespace internal {

// Number of trials needed so that an all-inlier sample of size s is drawn with
// probability `confidence` when a fraction w of the data are inliers.
inline int AdaptiveTrials(double inlier_ratio, int sample_size, double confidence,
                          int max_trials) {
  if (inlier_ratio <= 0.0) return max_trials;
  const double all_inlier = std::pow(inlier_ratio, sample_size);
  if (all_inlier >= 1.0) return 1;
  const double denom = std::log(1.0 - all_inlier);
  if (!(denom < 0.0)) return max_trials;
  const double trials = std::ceil(std::log(1.0 - confidence) / denom);
  return trials >= max_trials ? max_trials : std::max(1, static_cast<int>(trials));
}

// Draws `size` distinct indices from [0, num_data) (partial Fisher-Yates).
inline void DrawSample(int num_data, int size, Rng* rng, std::vector<int>* pool,
                       std::vector<int>* sample) {
  sample->resize(size);
  for (int i = 0; i < size; ++i) {
    std::uniform_int_distribution<int> pick(i, num_data - 1);
    const int j = pick(*rng);
    std::swap((*pool)[i], (*pool)[j]);
    (*sample)[i] = (*pool)[i];
  }
}

struct ModelScore {
  int num_inliers = 0;
  double cost = std::numeric_limits<double>::infinity();
  bool BetterThan(const ModelScore& other) const {
    return num_inliers > other.num_inliers ||
           (num_inliers == other.num_inliers && cost < other.cost);
  }
};

inline ModelScore ScoreResiduals(const std::vector<double>& residuals, double max_residual,
                                 std::vector<int>* inliers) {
  ModelScore score;
  score.cost = 0.0;
  const double max_sq = max_residual * max_residual;
  if (inliers) inliers->clear();
  for (size_t i = 0; i < residuals.size(); ++i) {
    const double r = residuals[i];
    if (r <= max_residual) {  // false for NaN
      ++score.num_inliers;
      score.cost += r * r;
      if (inliers) inliers->push_back(static_cast<int>(i));
    } else {
      score.cost += max_sq;
    }
  }
  return score;
}

}  // namespace internal

template <typename Estimator>
RansacReport<typename Estimator::Model> RunRansac(const RansacOptions& options,
                                                  const Estimator& estimator, int num_data) {
  using Model = typename Estimator::Model;
  options.Check();
  constexpr int kSampleSize = Estimator::kMinSampleSize;
  RansacReport<Model> report;
  if (num_data < kSampleSize) return report;

  Rng rng(options.random_seed);
  std::vector<int> pool(num_data);
  for (int i = 0; i < num_data; ++i) pool[i] = i;
  std::vector<int> sample;
  std::vector<Model> models;
  std::vector<double> residuals;
  internal::ModelScore best_score;
  Model best_model{};
  int needed_trials = options.max_trials;
  for (int trial = 0; trial < std::max(needed_trials, options.min_trials); ++trial) {
    ++report.num_trials;
    internal::DrawSample(num_data, kSampleSize, &rng, &pool, &sample);
    models.clear();
    estimator.Estimate(sample, &models);
    for (const Model& model : models) {
      estimator.Residuals(model, &residuals);
      const internal::ModelScore score =
          internal::ScoreResiduals(residuals, options.max_residual, nullptr);
      if (!score.BetterThan(best_score)) continue;
      best_score = score;
      best_model = model;
      needed_trials = internal::AdaptiveTrials(
          static_cast<double>(score.num_inliers) / num_data, kSampleSize, options.confidence,
          options.max_trials);
    }
  }
  if (best_score.num_inliers < kSampleSize) return report;

  estimator.Residuals(best_model, &residuals);
  internal::ScoreResiduals(residuals, options.max_residual, &report.inliers);
  for (int round = 0; round < options.refine_rounds; ++round) {
    Model refined = best_model;
    if (!estimator.Refine(report.inliers, &refined)) break;
    estimator.Residuals(refined, &residuals);
    std::vector<int> refined_inliers;
    const internal::ModelScore score =
        internal::ScoreResiduals(residuals, options.max_residual, &refined_inliers);
    if (score.num_inliers < best_score.num_inliers) break;
    const bool unchanged = refined_inliers == report.inliers;
    best_score = score;
    best_model = refined;
    report.inliers = std::move(refined_inliers);
    if (unchanged) break;
  }
  report.success = true;
  report.model = best_model;
  return report;
}

}  // namespace duskmap
