#include "slam/core/json_codec.h"

namespace duskmap {
namespace json_codec_internal {
namespace {

std::vector<std::string> SplitDots(const std::string& dotted) {
  std::vector<std::string> parts;
  size_t start = 0;
  for (size_t dot = dotted.find('.'); dot != std::string::npos; dot = dotted.find('.', start)) {
    parts.push_back(dotted.substr(start, dot - start));
    start = dot + 1;
  }
  parts.push_back(dotted.substr(start));
  return parts;
}

}  // namespace

const nlohmann::json* FindPath(const nlohmann::json& object, const std::string& dotted) {
  const nlohmann::json* at = &object;
  for (const std::string& key : SplitDots(dotted)) {
    if (!at->is_object() || !at->contains(key)) return nullptr;
    at = &at->at(key);
  }
  return at;
}

void ErasePath(nlohmann::json* object, const std::string& dotted) {
  const std::vector<std::string> parts = SplitDots(dotted);
  nlohmann::json* at = object;
  for (size_t i = 0; i + 1 < parts.size(); ++i) {
    if (!at->is_object() || !at->contains(parts[i])) return;
    at = &(*at)[parts[i]];
  }
  if (at->is_object()) at->erase(parts.back());
}

}  // namespace json_codec_internal

void JsonCodecReader::RejectDerived(const JsonFields& child, const JsonDerivedKeys& derived) {
  for (const JsonDerivedKey& d : derived) {
    SLAM_THROW_IF_NOT(ConfigError, json_codec_internal::FindPath(child.object(), d.path) == nullptr)
        << child.where() << "." << d.path << ": not set here; " << d.set_by << " sets it";
  }
}

}  // namespace duskmap
