#include "slam/registration/registration_options_json.h"

#include <string>

namespace duskmap {
namespace {

void ReadMatching(JsonFields f, NndrMatcherOptions* o) {
  f.Read("float_ratio", &o->float_ratio);
  f.Read("binary_ratio", &o->binary_ratio);
  std::string search = "auto";
  f.Read("search", &search);
  if (search == "auto") {
    o->search = NndrSearch::kAuto;
  } else if (search == "brute_force") {
    o->search = NndrSearch::kBruteForce;
  } else if (search == "kd_tree") {
    o->search = NndrSearch::kKdTree;
  } else {
    SLAM_THROW(ConfigError) << f.where() << ".search: expected auto, brute_force or kd_tree, got '"
                            << search << "'";
  }
  f.Read("kd_min_train_size", &o->kd_min_train_size);
  f.Read("kd_trees", &o->kd_trees);
  f.Read("kd_checks", &o->kd_checks);
  f.Read("unique", &o->unique);
  f.Read("random_seed", &o->random_seed);
  f.RejectUnknown();
}

void ReadPnp(JsonFields f, PnpRansacOptions* o) {
  f.Read("max_reprojection_error_px", &o->max_reprojection_error_px);
  f.Read("confidence", &o->confidence);
  f.Read("max_trials", &o->max_trials);
  f.Read("refine_rounds", &o->refine_rounds);
  std::string solver = o->solver == PnpMinimalSolver::kP3P ? "p3p" : "ap3p";
  f.Read("solver", &solver);
  if (solver == "p3p") {
    o->solver = PnpMinimalSolver::kP3P;
  } else if (solver == "ap3p") {
    o->solver = PnpMinimalSolver::kAP3P;
  } else {
    SLAM_THROW(ConfigError) << f.where() << ".solver: expected p3p or ap3p, got '" << solver
                            << "'";
  }
  f.Read("random_seed", &o->random_seed);
  f.RejectUnknown();
}

void ReadBundleAdjustment(JsonFields f, LocalBundleAdjustmentOptions* o) {
  f.Read("enabled", &o->enabled);
  f.Read("pixel_sigma_px", &o->pixel_sigma_px);
  f.Read("huber_delta_px", &o->huber_delta_px);
  f.Read("outlier_chi2", &o->outlier_chi2);
  f.Read("stereo_baseline_m", &o->stereo_baseline_m);
  f.Read("first_iterations", &o->first_iterations);
  f.Read("iterations", &o->iterations);
  f.RejectUnknown();
}

void ReadInformation(JsonFields f, LinkInformationOptions* o) {
  f.Read("variance_median_ratio", &o->variance_median_ratio);
  f.Read("missing_depth_scale", &o->missing_depth_scale);
  f.Read("min_linear_variance_m2", &o->min_linear_variance_m2);
  f.Read("min_angular_variance_rad2", &o->min_angular_variance_rad2);
  f.Read("max_linear_variance_m2", &o->max_linear_variance_m2);
  f.RejectUnknown();
}

}  // namespace

RegistrationOptions ReadRegistrationOptions(JsonFields& f) {
  RegistrationOptions o;
  f.Read("min_inliers", &o.min_inliers);
  f.Read("second_pass", &o.second_pass);
  f.Read("guess_window_px", &o.guess_window_px);
  f.Read("second_pass_with_external_matcher", &o.second_pass_with_external_matcher);
  ReadMatching(f.Child("matching"), &o.matching);
  ReadPnp(f.Child("pnp"), &o.pnp);
  ReadBundleAdjustment(f.Child("bundle_adjustment"), &o.bundle_adjustment);
  ReadInformation(f.Child("information"), &o.information);
  f.RejectUnknown();
  o.Check();
  return o;
}

}  // namespace duskmap
