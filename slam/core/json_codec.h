// One declaration of a struct's JSON fields gives its reader and its writer,
// so a key cannot be spelt one way when written and another when read.
//
//   template <>
//   struct JsonCodec<PnpRansacOptions> {
//     template <typename Fields, typename Options>
//     static void Visit(Fields& f, Options& o) {     // Options: T or const T
//       f("max_reprojection_error_px", o.max_reprojection_error_px);
//       f("solver", o.solver);  // an enum with JsonEnumNames: written by name
//     }
//   };
//
//   PnpRansacOptions o = ReadJsonOptions<PnpRansacOptions>(fields);  // strict, Check()ed
//   nlohmann::json j = ToJsonObject(o);                              // every field
//
// A field is a value JsonFields::Read takes (numbers with range checks,
// strings, bools, vectors, maps), an enum with JsonEnumNames, an Eigen
// vector of doubles (Vector2d, Vector3d: so many numbers), a struct with its
// own JsonCodec (a nested object, read with its unknown keys rejected by their
// full path), a std::vector of such structs (an array of objects, each named
// "key[i]" in errors), or a std::optional of any of these (null when empty).
// Reading keeps a field's default when its key is absent; a key declared
// with JsonRequired must be present:
//       f("name", o.name, JsonRequired{});   // "<where>: missing key 'name'"
// and a list declared with JsonOmitEmpty is not written when empty:
//       f("assets", o.assets, JsonOmitEmpty{});
// A struct's codec lives beside the struct's module
// (`<module>/<name>_json.h`), so whoever composes the struct composes its codec.
//
// Why a field list and not NLOHMANN_DEFINE_TYPE_*: those macros either
// require every key or silently ignore unknown ones, cannot name a bad value
// by its path, write enums as integers, and cannot leave out the fields a
// composing struct sets itself (JsonDerivedKeys below).
#pragma once

#include <cstring>
#include <iterator>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "slam/core/check.h"
#include "slam/core/json_fields.h"

namespace duskmap {

// Specialised per struct (see above).
template <typename T>
struct JsonCodec;

// Specialised per enum: static constexpr std::pair<E, const char*> kNames[].
template <typename E>
struct JsonEnumNames;

// Fields of a nested struct that the composing struct fills in itself (the
// engine's random seed copied into RANSAC's, ...): a config that sets one is
// refused with the key that does, and the writer leaves them out.
struct JsonDerivedKey {
  const char* path;    // dotted, relative to the nested object: "pnp.random_seed"
  const char* set_by;  // the key that sets it, as the reader should write it
};
using JsonDerivedKeys = std::vector<JsonDerivedKey>;

// Marks a key the reader requires (the writer always writes every field).
struct JsonRequired {};

// Marks a list the writer leaves out when it is empty (a key that files
// written before the list existed do not have); the reader reads it as any
// other field, absent = empty.
struct JsonOmitEmpty {};

namespace json_codec_internal {

template <typename T, typename = void>
struct HasCodec : std::false_type {};
template <typename T>
struct HasCodec<T, std::void_t<decltype(sizeof(JsonCodec<T>))>> : std::true_type {};

template <typename T, typename = void>
struct HasEnumNames : std::false_type {};
template <typename T>
struct HasEnumNames<T, std::void_t<decltype(JsonEnumNames<T>::kNames)>> : std::true_type {};

template <typename T>
struct IsOptional : std::false_type {};
template <typename T>
struct IsOptional<std::optional<T>> : std::true_type {};

// A std::vector of structs with a codec.
template <typename T>
struct IsCodecVector : std::false_type {};
template <typename T>
struct IsCodecVector<std::vector<T>> : HasCodec<T> {};

// An Eigen column vector of doubles of fixed size (Vector2d, Vector3d, ...).
template <typename T>
struct IsEigenVector : std::false_type {};
template <int N, int Options, int MaxRows>
struct IsEigenVector<Eigen::Matrix<double, N, 1, Options, MaxRows, 1>>
    : std::bool_constant<(N > 0)> {};

template <typename T, typename = void>
struct HasCheck : std::false_type {};
template <typename T>
struct HasCheck<T, std::void_t<decltype(std::declval<const T&>().Check())>> : std::true_type {};

// "a, b or c"
template <typename E>
std::string EnumChoices() {
  std::string out;
  const size_t n = std::size(JsonEnumNames<E>::kNames);
  for (size_t i = 0; i < n; ++i) {
    if (i > 0) out += i + 1 == n ? " or " : ", ";
    out += JsonEnumNames<E>::kNames[i].second;
  }
  return out;
}

// The value at a dotted path of `object`, or nullptr.
const nlohmann::json* FindPath(const nlohmann::json& object, const std::string& dotted);
// Removes the value at a dotted path (and nothing when absent).
void ErasePath(nlohmann::json* object, const std::string& dotted);

}  // namespace json_codec_internal

// The name of an enum value (its JsonEnumNames entry).
template <typename E>
const char* JsonEnumName(E value) {
  for (const auto& [v, name] : JsonEnumNames<E>::kNames) {
    if (v == value) return name;
  }
  SLAM_CHECK_MSG(false, "JsonEnumName: an enum value without a name");
  return "";
}

// The enum value named `name`; ConfigError "<where>: expected a, b or c, got 'x'".
template <typename E>
E ParseJsonEnum(const std::string& name, const std::string& where) {
  for (const auto& [v, n] : JsonEnumNames<E>::kNames) {
    if (name == n) return v;
  }
  SLAM_THROW(ConfigError) << where << ": expected " << json_codec_internal::EnumChoices<E>()
                          << ", got '" << name << "'";
  return JsonEnumNames<E>::kNames[0].first;  // not reached
}

// Reads the fields a JsonCodec declares from JsonFields.
class JsonCodecReader {
 public:
  explicit JsonCodecReader(JsonFields* fields) : fields_(fields) {}

  template <typename T>
  void operator()(const char* key, T& value, const JsonDerivedKeys& derived = {}) {
    using namespace json_codec_internal;
    if constexpr (HasCodec<T>::value) {
      JsonFields child = fields_->Child(key);
      RejectDerived(child, derived);
      ReadFields(child, &value);
    } else if constexpr (HasEnumNames<T>::value) {
      if (!fields_->Has(key)) {
        fields_->Read(key, &value);  // marks it used; absent keeps the default
        return;
      }
      std::string name;
      fields_->Read(key, &name);
      value = ParseJsonEnum<T>(name, fields_->where() + "." + key);
    } else if constexpr (IsOptional<T>::value) {
      if (fields_->Has(key) && fields_->object().at(key).is_null()) {
        nlohmann::json null;
        fields_->Read(key, &null);  // marks it used
        value.reset();
        return;
      }
      const bool present = fields_->Has(key);
      typename T::value_type item = value.value_or(typename T::value_type());
      (*this)(key, item, derived);
      if (present) value = std::move(item);
    } else if constexpr (IsCodecVector<T>::value) {
      nlohmann::json items;
      const bool present = fields_->Has(key);
      fields_->Read(key, &items);  // marks it used
      if (!present) return;
      const std::string where = fields_->where() + "." + key;
      SLAM_THROW_IF_NOT(ConfigError, items.is_array())
          << where << ": wrong type (" << items.type_name() << ", expected an array)";
      T out(items.size());
      for (size_t i = 0; i < items.size(); ++i) {
        JsonFields item(items[i], where + "[" + std::to_string(i) + "]");
        ReadFields(item, &out[i]);
      }
      value = std::move(out);
    } else if constexpr (IsEigenVector<T>::value) {
      std::vector<double> numbers;
      const bool present = fields_->Has(key);
      fields_->Read(key, &numbers);
      if (!present) return;
      SLAM_THROW_IF_NOT(ConfigError, numbers.size() == static_cast<size_t>(T::RowsAtCompileTime))
          << fields_->where() << "." << key << ": expected " << T::RowsAtCompileTime
          << " numbers, got " << numbers.size();
      for (int i = 0; i < T::RowsAtCompileTime; ++i) value[i] = numbers[static_cast<size_t>(i)];
    } else {
      fields_->Read(key, &value);
    }
  }

  // A key that must be present: ConfigError "<where>: missing key 'key'".
  template <typename T>
  void operator()(const char* key, T& value, JsonRequired) {
    SLAM_THROW_IF_NOT(ConfigError, fields_->Has(key))
        << fields_->where() << ": missing key '" << key << "'";
    (*this)(key, value);
  }

  template <typename T>
  void operator()(const char* key, T& value, JsonOmitEmpty) {
    (*this)(key, value);
  }

  // Reads every field of *value that `fields` holds, then rejects the keys
  // no field declared. No Check(): the caller checks the whole struct.
  template <typename T>
  static void ReadFields(JsonFields& fields, T* value) {
    JsonCodecReader reader(&fields);
    JsonCodec<T>::Visit(reader, *value);
    fields.RejectUnknown();
  }

 private:
  static void RejectDerived(const JsonFields& child, const JsonDerivedKeys& derived);

  JsonFields* fields_;
};

// Writes the fields a JsonCodec declares into a JSON object.
class JsonCodecWriter {
 public:
  explicit JsonCodecWriter(nlohmann::json* object) : object_(object) {}

  template <typename T>
  void operator()(const char* key, const T& value, const JsonDerivedKeys& derived = {}) {
    using namespace json_codec_internal;
    if constexpr (HasCodec<T>::value) {
      nlohmann::json child = WriteFields(value);
      for (const JsonDerivedKey& d : derived) ErasePath(&child, d.path);
      (*object_)[key] = std::move(child);
    } else if constexpr (HasEnumNames<T>::value) {
      (*object_)[key] = JsonEnumName(value);
    } else if constexpr (IsOptional<T>::value) {
      if (value) {
        (*this)(key, *value, derived);
      } else {
        (*object_)[key] = nullptr;
      }
    } else if constexpr (IsCodecVector<T>::value) {
      nlohmann::json items = nlohmann::json::array();
      for (const auto& item : value) items.push_back(WriteFields(item));
      (*object_)[key] = std::move(items);
    } else if constexpr (IsEigenVector<T>::value) {
      nlohmann::json numbers = nlohmann::json::array();
      for (int i = 0; i < T::RowsAtCompileTime; ++i) numbers.push_back(value[i]);
      (*object_)[key] = std::move(numbers);
    } else {
      (*object_)[key] = value;
    }
  }

  template <typename T>
  void operator()(const char* key, const T& value, JsonRequired) {
    (*this)(key, value);
  }

  template <typename T>
  void operator()(const char* key, const T& value, JsonOmitEmpty) {
    if (!IsEmptyValue(value)) (*this)(key, value);
  }

  template <typename T>
  static bool IsEmptyValue(const T& value) {
    return value.empty();
  }
  template <typename T>
  static bool IsEmptyValue(const std::optional<T>& value) {
    return !value.has_value();
  }

  template <typename T>
  static nlohmann::json WriteFields(const T& value) {
    nlohmann::json object = nlohmann::json::object();
    JsonCodecWriter writer(&object);
    JsonCodec<T>::Visit(writer, value);
    return object;
  }

 private:
  nlohmann::json* object_;
};

// Every field of `value` as a JSON object (keys sorted, enums by name).
template <typename T>
nlohmann::json ToJsonObject(const T& value) {
  return JsonCodecWriter::WriteFields(value);
}

// Reads T from `fields` (absent keys keep T's defaults; unknown keys are
// refused with their path) and, when T has one, runs its Check(); a failed
// check is rethrown as "<where>: <the check's message>".
template <typename T>
T ReadJsonOptions(JsonFields& fields) {
  T value;
  JsonCodecReader::ReadFields(fields, &value);
  if constexpr (json_codec_internal::HasCheck<T>::value) {
    try {
      value.Check();
    } catch (const ConfigError& e) {
      SLAM_THROW(ConfigError) << fields.where() << ": " << e.what();
    }
  }
  return value;
}

// The same from a JSON value; `where` names it in errors.
template <typename T>
T ReadJsonOptions(const nlohmann::json& object, const std::string& where) {
  JsonFields fields(object, where);
  return ReadJsonOptions<T>(fields);
}

}  // namespace duskmap
