#include "slam/core/json_fields.h"

namespace duskmap {

JsonFields::JsonFields(const nlohmann::json& object, std::string where)
    : object_(object), where_(std::move(where)) {
  if (object_.is_null()) object_ = nlohmann::json::object();
  SLAM_THROW_IF_NOT(ConfigError, object_.is_object())
      << where_ << ": expected a JSON object, got " << object_.type_name();
}

JsonFields JsonFields::Child(const std::string& key) {
  used_.insert(key);
  if (!object_.contains(key)) return JsonFields(nlohmann::json::object(), where_ + "." + key);
  return JsonFields(object_.at(key), where_ + "." + key);
}

const nlohmann::json& JsonFields::Raw(const std::string& key) {
  used_.insert(key);
  SLAM_THROW_IF_NOT(ConfigError, Has(key)) << where_ << ": missing key '" << key << "'";
  return object_.at(key);
}

void JsonFields::RejectUnknown() const {
  for (auto it = object_.begin(); it != object_.end(); ++it) {
    if (it.key() == kCommentKey) continue;
    SLAM_THROW_IF_NOT(ConfigError, used_.count(it.key()) > 0)
        << where_ << ": unknown key '" << it.key() << "'";
  }
}

}  // namespace duskmap
