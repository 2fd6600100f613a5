#include "slam/core/json_fields.h"

#include <fstream>
#include <sstream>
#include <vector>

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

nlohmann::json ParseJsonText(const std::string& text, const std::string& where) {
  // The parser reports keys as it meets them: one set of seen keys per open
  // object finds a key given twice (nlohmann keeps the last one silently).
  struct Open {
    bool array = false;
    std::string key;             // the key that holds it ("" at the top, or in an array)
    std::set<std::string> keys;  // objects: the keys seen so far
  };
  std::vector<Open> open;
  std::string last_key;
  std::string duplicate;
  const nlohmann::json::parser_callback_t check_keys =
      [&](int /*depth*/, nlohmann::json::parse_event_t event, nlohmann::json& parsed) {
        using Event = nlohmann::json::parse_event_t;
        const bool in_object = !open.empty() && !open.back().array;
        if (event == Event::object_start || event == Event::array_start) {
          open.push_back({event == Event::array_start, in_object ? last_key : std::string(), {}});
        } else if (event == Event::object_end || event == Event::array_end) {
          open.pop_back();
        } else if (event == Event::key) {
          last_key = parsed.get<std::string>();
          if (!open.back().keys.insert(last_key).second && duplicate.empty()) {
            for (const Open& o : open) {
              if (!o.key.empty()) duplicate += o.key + (o.array ? "[]." : ".");
            }
            duplicate += last_key;
          }
        }
        return true;
      };
  nlohmann::json json;
  try {
    json = nlohmann::json::parse(text, check_keys);
  } catch (const nlohmann::json::parse_error& e) {
    // e.byte is the 1-based offset where parsing stopped.
    size_t line = 1, column = 1;
    for (size_t i = 0; i + 1 < e.byte && i < text.size(); ++i) {
      if (text[i] == '\n') {
        ++line;
        column = 1;
      } else {
        ++column;
      }
    }
    std::string reason = e.what();
    const size_t colon = reason.find(": ");
    if (colon != std::string::npos) reason = reason.substr(colon + 2);
    SLAM_THROW(ConfigError) << where << ":" << line << ":" << column << ": invalid JSON (" << reason
                            << ")";
  }
  SLAM_THROW_IF_NOT(ConfigError, duplicate.empty())
      << where << ": key '" << duplicate << "' is given twice";
  return json;
}

nlohmann::json ReadJsonFile(const std::string& path) {
  std::ifstream in(path);
  SLAM_THROW_IF_NOT(ConfigError, in.good()) << path << ": cannot open file";
  std::stringstream buffer;
  buffer << in.rdbuf();
  return ParseJsonText(buffer.str(), path);
}

}  // namespace duskmap
