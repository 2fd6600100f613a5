// The odometry cache's validation results' names (slam/core/json_codec.h),
// their one spelling, which CacheValidationName returns too.
#pragma once

#include <utility>

#include "slam/core/json_codec.h"
#include "slam/engine/odometry_cache.h"

namespace duskmap {

template <>
struct JsonEnumNames<CacheValidation> {
  static constexpr std::pair<CacheValidation, const char*> kNames[] = {
      {CacheValidation::kApplied, "applied"},
      {CacheValidation::kWaiting, "waiting"},
      {CacheValidation::kRejected, "rejected"}};
};

}  // namespace duskmap
