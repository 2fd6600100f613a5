// Reads RegistrationOptions from a JSON object (strict: unknown keys throw
// ConfigError with their path). Keys mirror the option fields:
//   {"min_inliers": 20, "second_pass": true, "guess_window_px": 40,
//    "second_pass_with_external_matcher": false,
//    "matching": {"float_ratio", "binary_ratio", "search": "auto|brute_force|kd_tree",
//                 "kd_min_train_size", "kd_trees", "kd_checks", "unique", "random_seed"},
//    "pnp": {"max_reprojection_error_px", "confidence", "max_trials", "refine_rounds",
//            "solver": "ap3p|p3p", "random_seed"},
//    "bundle_adjustment": {"enabled", "pixel_sigma_px", "huber_delta_px", "outlier_chi2",
//                          "stereo_baseline_m", "first_iterations", "iterations"},
//    "information": {"variance_median_ratio", "missing_depth_scale", "min_linear_variance_m2",
//                    "min_angular_variance_rad2", "max_linear_variance_m2"}}
#pragma once

#include "slam/core/json_fields.h"
#include "slam/registration/transform_estimation.h"

namespace duskmap {

RegistrationOptions ReadRegistrationOptions(JsonFields& fields);

}  // namespace duskmap
