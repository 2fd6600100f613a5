// Reads an options struct from a JSON object while remembering which keys
// were consumed, so that unknown (mistyped) keys are rejected with their full
// path instead of being silently ignored.
//
//   JsonFields f(json, "configs/x.json:camera");
//   f.Read("width", &options.width);        // keeps the default when absent
//   options.Check();
//   f.RejectUnknown();                      // throws on any key not read
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>
#include <set>
#include <string>
#include <type_traits>
#include <vector>

#include <nlohmann/json.hpp>

#include "slam/core/check.h"
#include "slam/core/json_reader.h"  // ReadJsonFile, ParseJsonText: where the objects come from

namespace duskmap {

class JsonFields {
  template <typename T>
  struct IsIntegerVector : std::false_type {};
  template <typename V>
  struct IsIntegerVector<std::vector<V>>
      : std::bool_constant<std::is_integral_v<V> && !std::is_same_v<V, bool>> {};

 public:
  // `where` names the object in errors, e.g. "configs/sunset.json:camera".
  JsonFields(const nlohmann::json& object, std::string where);

  bool Has(const std::string& key) const { return object_.contains(key); }

  // Reads key into *value when present; throws ConfigError on a type
  // mismatch. Integers (and vectors of them) are converted with checks: a
  // fraction, or a value outside the type's range, is an error, never
  // truncated or wrapped.
  template <typename T>
  void Read(const std::string& key, T* value) {
    used_.insert(key);
    if (!object_.contains(key)) return;
    const nlohmann::json& item = object_.at(key);
    if constexpr (std::is_integral_v<T> && !std::is_same_v<T, bool>) {
      *value = CheckedInteger<T>(item, where_ + "." + key);
    } else if constexpr (IsIntegerVector<T>::value) {
      SLAM_THROW_IF_NOT(ConfigError, item.is_array())
          << where_ << "." << key << ": wrong type (" << item.type_name() << ", expected an array)";
      T out;
      for (size_t i = 0; i < item.size(); ++i) {
        out.push_back(CheckedInteger<typename T::value_type>(
            item[i], where_ + "." + key + "[" + std::to_string(i) + "]"));
      }
      *value = std::move(out);
    } else {
      try {
        *value = item.get<T>();
      } catch (const nlohmann::json::exception& e) {
        SLAM_THROW(ConfigError) << where_ << "." << key << ": wrong type (" << item.type_name()
                                << ")";
      }
    }
  }

  // The integer in `item`: a JSON integer, or a number with no fraction,
  // within T's range; otherwise ConfigError naming `where`.
  template <typename T>
  static T CheckedInteger(const nlohmann::json& item, const std::string& where) {
    SLAM_THROW_IF_NOT(ConfigError, item.is_number())
        << where << ": wrong type (" << item.type_name() << ", expected an integer)";
    long double v = 0;
    if (item.is_number_unsigned()) {
      v = static_cast<long double>(item.get<uint64_t>());
    } else if (item.is_number_integer()) {
      v = static_cast<long double>(item.get<int64_t>());
    } else {
      const double d = item.get<double>();
      SLAM_THROW_IF_NOT(ConfigError, std::isfinite(d) && std::floor(d) == d)
          << where << ": expected an integer, got " << item.dump();
      v = d;
    }
    SLAM_THROW_IF_NOT(ConfigError, v >= static_cast<long double>(std::numeric_limits<T>::min()) &&
                                       v <= static_cast<long double>(std::numeric_limits<T>::max()))
        << where << ": " << item.dump() << " is out of range (" << +std::numeric_limits<T>::min()
        << " to " << +std::numeric_limits<T>::max() << ")";
    return static_cast<T>(v);
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
  const nlohmann::json& object() const { return object_; }

  // Throws ConfigError naming the first key that was never read; the key
  // "_comment" (free text for the reader of a config) is always allowed.
  void RejectUnknown() const;
  static constexpr const char* kCommentKey = "_comment";

 private:
  nlohmann::json object_;
  std::string where_;
  std::set<std::string> used_;
};

}  // namespace duskmap
