#include "slam/features/matcher_options.h"

#include "slam/core/check.h"

namespace duskmap {

void MatcherOptions::Check() const {
  SLAM_THROW_IF_NOT(ConfigError, type == "nndr" || type == "superglue")
      << "matcher.type: must be \"nndr\" or \"superglue\", got \"" << type << "\"";
  if (type == "superglue") superglue.Check();
}

std::unique_ptr<FeatureMatcher> CreateFeatureMatcher(const MatcherOptions& options) {
  options.Check();
  if (options.type == "nndr") return nullptr;
  return std::make_unique<SuperGlueMatcher>(options.superglue);
}

}  // namespace duskmap
