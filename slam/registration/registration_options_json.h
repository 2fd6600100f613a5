// JSON codecs of registration's options (slam/core/json_codec.h). Keys are
// the option fields:
//   {"min_inliers": 20, "second_pass": true, "guess_window_px": 40,
//    "matching": {"float_ratio": 0.6, "search": "auto|brute_force|kd_tree", ...},
//    "pnp": {"max_reprojection_error_px": 4, "solver": "ap3p|p3p", ...},
//    "bundle_adjustment": {...}, "information": {...}}
#pragma once

#include <utility>

#include "slam/core/json_codec.h"
#include "slam/features/feature_options_json.h"
#include "slam/registration/transform_estimation.h"

namespace duskmap {

template <>
struct JsonEnumNames<NndrSearch> {
  static constexpr std::pair<NndrSearch, const char*> kNames[] = {
      {NndrSearch::kAuto, "auto"},
      {NndrSearch::kBruteForce, "brute_force"},
      {NndrSearch::kKdTree, "kd_tree"}};
};

template <>
struct JsonEnumNames<PnpMinimalSolver> {
  static constexpr std::pair<PnpMinimalSolver, const char*> kNames[] = {
      {PnpMinimalSolver::kAP3P, "ap3p"}, {PnpMinimalSolver::kP3P, "p3p"}};
};

template <>
struct JsonCodec<NndrMatcherOptions> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    f("float_ratio", o.float_ratio);
    f("binary_ratio", o.binary_ratio);
    f("binary_distance", o.binary_distance);
    f("search", o.search);
    f("kd_min_train_size", o.kd_min_train_size);
    f("kd_trees", o.kd_trees);
    f("kd_checks", o.kd_checks);
    f("unique", o.unique);
    f("random_seed", o.random_seed);
  }
};

template <>
struct JsonCodec<PnpRansacOptions> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    f("max_reprojection_error_px", o.max_reprojection_error_px);
    f("confidence", o.confidence);
    f("max_trials", o.max_trials);
    f("refine_rounds", o.refine_rounds);
    f("solver", o.solver);
    f("random_seed", o.random_seed);
  }
};

template <>
struct JsonCodec<LocalBundleAdjustmentOptions> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    f("enabled", o.enabled);
    f("pixel_sigma_px", o.pixel_sigma_px);
    f("huber_delta_px", o.huber_delta_px);
    f("outlier_chi2", o.outlier_chi2);
    f("stereo_baseline_m", o.stereo_baseline_m);
    f("first_iterations", o.first_iterations);
    f("iterations", o.iterations);
  }
};

template <>
struct JsonCodec<LinkInformationOptions> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    f("variance_median_ratio", o.variance_median_ratio);
    f("missing_depth_scale", o.missing_depth_scale);
    f("min_linear_variance_m2", o.min_linear_variance_m2);
    f("min_angular_variance_rad2", o.min_angular_variance_rad2);
    f("max_linear_variance_m2", o.max_linear_variance_m2);
  }
};

template <>
struct JsonCodec<RegistrationOptions> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    f("min_inliers", o.min_inliers);
    f("second_pass", o.second_pass);
    f("guess_window_px", o.guess_window_px);
    f("second_pass_with_external_matcher", o.second_pass_with_external_matcher);
    f("matching", o.matching);
    f("pnp", o.pnp);
    f("bundle_adjustment", o.bundle_adjustment);
    f("information", o.information);
  }
};

}  // namespace duskmap
