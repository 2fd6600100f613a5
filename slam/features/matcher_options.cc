#include "slam/features/matcher_options.h"

#include "slam/core/check.h"

namespace duskmap {

void MatcherOptions::Check() const {
  SLAM_THROW_IF_NOT(ConfigError, type == "nndr" || type == "superglue")
      << "matcher.type: must be \"nndr\" or \"superglue\", got \"" << type << "\"";
  if (type == "superglue") superglue.Check();
}

MatcherOptions ReadMatcherOptions(JsonFields& fields) {
  MatcherOptions o;
  fields.Read("type", &o.type);
  JsonFields superglue = fields.Child("superglue");
  superglue.Read("model_path", &o.superglue.model_path);
  superglue.Read("match_threshold", &o.superglue.match_threshold);
  superglue.RejectUnknown();
  fields.RejectUnknown();
  o.Check();
  return o;
}

nlohmann::json MatcherOptionsToJson(const MatcherOptions& o) {
  return {{"type", o.type},
          {"superglue",
           {{"model_path", o.superglue.model_path},
            {"match_threshold", o.superglue.match_threshold}}}};
}

std::unique_ptr<FeatureMatcher> CreateFeatureMatcher(const MatcherOptions& options) {
  options.Check();
  if (options.type == "nndr") return nullptr;
  return std::make_unique<SuperGlueMatcher>(options.superglue);
}

}  // namespace duskmap
