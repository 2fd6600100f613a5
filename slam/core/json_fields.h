// Reads an options struct from a JSON object while remembering which keys
// were consumed, so that unknown (mistyped) keys are rejected with their full
// path instead of being silently ignored.
//
//   JsonFields f(json, "configs/x.json:camera");
//   f.Read("width", &options.width);        // keeps the default when absent
//   options.Check();
//   f.RejectUnknown();                      // throws on any key not read
#pragma once

#include <set>
#include <string>

#include <nlohmann/json.hpp>

#include "slam/core/check.h"

namespace duskmap {

class JsonFields {
 public:
  // `where` names the object in errors, e.g. "configs/sunset.json:camera".
  JsonFields(const nlohmann::json& object, std::string where);

  bool Has(const std::string& key) const { return object_.contains(key); }

  // Reads key into *value when present; throws ConfigError on a type mismatch.
  template <typename T>
  void Read(const std::string& key, T* value) {
    used_.insert(key);
    if (!object_.contains(key)) return;
    try {
      *value = object_.at(key).get<T>();
    } catch (const nlohmann::json::exception& e) {
      SLAM_THROW(ConfigError) << where_ << "." << key << ": wrong type ("
                              << object_.at(key).type_name() << ")";
    }
  }
  // Like Read, but the key must be present.
  template <typename T>
  void ReadRequired(const std::string& key, T* value) {
    SLAM_THROW_IF_NOT(ConfigError, Has(key)) << where_ << ": missing key '" << key << "'";
    Read(key, value);
  }

  // The sub-object at key (an empty object when absent), marked as used.
  JsonFields Child(const std::string& key);
  const nlohmann::json& Raw(const std::string& key);
  const std::string& where() const { return where_; }

  // Throws ConfigError naming the first key that was never read; the key
  // "_comment" (free text for the reader of a config) is always allowed.
  void RejectUnknown() const;
  static constexpr const char* kCommentKey = "_comment";

 private:
  nlohmann::json object_;
  std::string where_;
  std::set<std::string> used_;
};

// Parses a JSON file; throws ConfigError("<path>: <problem>") when it cannot.
nlohmann::json ReadJsonFile(const std::string& path);

}  // namespace duskmap
