// The registration statuses' names (slam/core/json_codec.h), their one
// spelling, which RegistrationStatusName returns too.
#pragma once

#include <utility>

#include "slam/core/json_codec.h"
#include "slam/registration/transform_estimation.h"

namespace duskmap {

template <>
struct JsonEnumNames<RegistrationStatus> {
  static constexpr std::pair<RegistrationStatus, const char*> kNames[] = {
      {RegistrationStatus::kAccepted, "accepted"},
      {RegistrationStatus::kNoFeatures, "no_features"},
      {RegistrationStatus::kTooFewMatches, "too_few_matches"},
      {RegistrationStatus::kPnpFailed, "pnp_failed"},
      {RegistrationStatus::kTooFewInliers, "too_few_inliers"},
      {RegistrationStatus::kSecondPassTooFewMatches, "second_pass_too_few_matches"},
      {RegistrationStatus::kSecondPassPnpFailed, "second_pass_pnp_failed"},
      {RegistrationStatus::kSecondPassTooFewInliers, "second_pass_too_few_inliers"},
      {RegistrationStatus::kBundleAdjustmentFailed, "ba_failed"},
      {RegistrationStatus::kBundleAdjustmentTooFewInliers, "ba_too_few_inliers"},
      {RegistrationStatus::kVarianceTooHigh, "variance_too_high"},
      {RegistrationStatus::kTranslationTooLong, "translation_too_long"}};
};

}  // namespace duskmap
