#include "slam/experiment/job_results.h"

#include <fstream>
#include <string>
#include <type_traits>
#include <utility>

#include "slam/core/check.h"
#include "slam/core/json_fields.h"
#include "slam/experiment/job_results_json.h"

namespace duskmap {
namespace {

template <typename T, typename = void>
struct HasRequiredKeys : std::false_type {};
template <typename T>
struct HasRequiredKeys<T, std::void_t<decltype(JsonCodec<T>::VisitRequired(
                              std::declval<int&>(), std::declval<const T&>()))>>
    : std::true_type {};

// Visits the keys a summary must hold (its codec's VisitRequired, or every
// key of a codec without one), nested summaries included; throws
// ConfigError "<where>: missing key 'k'" at the first one `object` lacks.
class RequiredKeyCheck {
 public:
  RequiredKeyCheck(const nlohmann::json& object, std::string where)
      : object_(object), where_(std::move(where)) {}

  template <typename T>
  static void Run(const nlohmann::json& object, const std::string& where, const T& value) {
    RequiredKeyCheck check(object, where);
    if constexpr (HasRequiredKeys<T>::value) {
      JsonCodec<T>::VisitRequired(check, value);
    } else {
      JsonCodec<T>::Visit(check, value);
    }
  }

  template <typename T>
  void operator()(const char* key, const T& value) {
    SLAM_THROW_IF_NOT(ConfigError, object_.contains(key)) << where_ << ": missing key '" << key << "'";
    if constexpr (json_codec_internal::HasCodec<T>::value) {
      Run(object_.at(key), where_ + "." + key, value);
    }
  }

 private:
  const nlohmann::json& object_;
  std::string where_;
};

// The typed summary in job_dir/summary.json: read strictly by its codec, then
// checked for the keys every summary holds.
template <typename T>
T ReadJobSummary(const std::filesystem::path& job_dir) {
  const std::string path = (job_dir / "summary.json").string();
  const nlohmann::json json = ReadSummary(job_dir);
  try {
    SLAM_THROW_IF_NOT(ConfigError, json.is_object())
        << path << ": expected an object, got " << json.type_name();
    T summary = ReadJsonOptions<T>(json, path);
    RequiredKeyCheck::Run(json, path, summary);
    return summary;
  } catch (const ConfigError& e) {
    SLAM_THROW(InputError) << e.what() << " (malformed job summary)";
  }
  return T();  // not reached
}

}  // namespace

void WriteSummary(const std::filesystem::path& job_dir, const nlohmann::json& summary) {
  const std::filesystem::path path = job_dir / "summary.json";
  std::ofstream out(path);
  out << summary.dump(1) << "\n";
  SLAM_THROW_IF_NOT(InputError, out.good()) << path.string() << ": cannot write";
}

nlohmann::json ReadSummary(const std::filesystem::path& job_dir) {
  const std::filesystem::path path = job_dir / "summary.json";
  std::ifstream in(path);
  SLAM_THROW_IF_NOT(InputError, in.good()) << path.string() << ": missing job summary";
  nlohmann::json json = nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
  SLAM_THROW_IF_NOT(InputError, !json.is_discarded())
      << path.string() << ": malformed job summary (not valid JSON)";
  return json;
}

LocalizationJobSummary ReadLocalizationJobSummary(const std::filesystem::path& job_dir) {
  return ReadJobSummary<LocalizationJobSummary>(job_dir);
}

MapJobSummary ReadMapJobSummary(const std::filesystem::path& job_dir) {
  return ReadJobSummary<MapJobSummary>(job_dir);
}

}  // namespace duskmap
