#include "slam/experiment/run_manifest.h"

#include <fstream>
#include <set>

#include <nlohmann/json.hpp>

#include "slam/core/check.h"
#include "slam/core/checksum.h"
#include "slam/core/input_file.h"
#include "slam/core/json_reader.h"
#include "slam/io/output_safety.h"

namespace duskmap {
namespace fs = std::filesystem;

namespace {
constexpr const char* kManifestFile = "run.json";
}  // namespace

SessionClock SessionClockOf(const std::vector<SessionInfo>& sessions,
                            const std::map<std::string, std::string>& configured) {
  SessionClock clock;
  for (const SessionInfo& session : sessions) {
    if (session.clock_time) clock[session.name] = ParseClockMinutes(*session.clock_time);
  }
  for (const auto& [name, hh_mm] : configured) clock[name] = ParseClockMinutes(hh_mm);
  return clock;
}

void SelectRunnableFeatures(const ExperimentOptions& options, const FeatureModels& models,
                            RunManifest* manifest) {
  manifest->features.clear();
  manifest->skipped_features.clear();
  const auto missing = [](const std::string& model, const char* key) -> std::string {
    if (model.empty()) {
      return std::string("no model configured (") + key +
             " in the engine config; see docs/features.md)";
    }
    if (!fs::exists(model)) return model + ": no such model file";
    return "";
  };
  for (const std::string& label : options.features) {
    const FeatureSetup& setup = options.FeatureSetupOf(label);
    std::string reason;
    if (setup.needs_model) reason = missing(models.superpoint, "features.superpoint.model_path");
    if (reason.empty() && setup.matcher == "superglue") {
      reason = missing(models.superglue, "matcher.superglue.model_path");
    }
    if (!reason.empty()) {
      manifest->skipped_features.push_back({label, reason});
      continue;
    }
    manifest->features.push_back(label);
  }
}

void WriteRunManifest(const RunManifest& m, const fs::path& results_dir) {
  nlohmann::json skipped = nlohmann::json::array();
  for (const SkippedFeature& s : m.skipped_features) {
    skipped.push_back({{"label", s.label}, {"reason", s.reason}});
  }
  const nlohmann::json json = {{"config", m.config_path},
                               {"dataset", m.dataset_path},
                               {"features", m.features},
                               {"skipped_features", skipped},
                               {"session_clock_min", m.session_clock},
                               {"shard", {{"index", m.shard_index}, {"count", m.shard_count}}},
                               {"configuration", m.configuration},
                               {"configuration_checksum", m.configuration_checksum}};
  std::error_code error;
  fs::create_directories(results_dir, error);
  WriteFileAtomically((results_dir / kManifestFile).string(),
                      [&](std::ostream& out) { out << json.dump(2) << "\n"; });
}

RunManifest ReadRunManifest(const fs::path& results_dir) {
  const fs::path path = results_dir / kManifestFile;
  RefuseNonRegularFile(path.string());  // before opening: a FIFO would block
  std::ifstream in(path);
  SLAM_THROW_IF_NOT(InputError, in.good())
      << path.string() << ": missing (not the results folder of `duskmap run`)";
  RunManifest m;
  try {
    const nlohmann::json json = ReadJsonFile(path.string());
    json.at("config").get_to(m.config_path);
    json.at("dataset").get_to(m.dataset_path);
    json.at("features").get_to(m.features);
    for (const auto& s : json.at("skipped_features")) {
      m.skipped_features.push_back({s.at("label").get<std::string>(),
                                    s.at("reason").get<std::string>()});
    }
    json.at("session_clock_min").get_to(m.session_clock);
    json.at("shard").at("index").get_to(m.shard_index);
    json.at("shard").at("count").get_to(m.shard_count);
    // (Absent in the run.json of older duskmap versions: such a run cannot
    // be resumed, only redone.)
    if (json.contains("configuration")) m.configuration = json.at("configuration");
    if (json.contains("configuration_checksum")) {
      json.at("configuration_checksum").get_to(m.configuration_checksum);
    }
  } catch (const nlohmann::json::exception& e) {
    SLAM_THROW(InputError) << path.string() << ": malformed run manifest (" << e.what() << ")";
  } catch (const ConfigError& e) {  // not JSON, or nested too deep
    SLAM_THROW(InputError) << e.what() << " (malformed run manifest)";
  }
  return m;
}

void SetRunConfiguration(const nlohmann::json& experiment, const nlohmann::json& engine,
                         const nlohmann::json& dataset_identity,
                         const nlohmann::json& feature_files, const std::string& version,
                         RunManifest* manifest) {
  manifest->configuration = {{"experiment", experiment},
                             {"engine", engine},
                             {"dataset", dataset_identity},
                             {"feature_files", feature_files},
                             {"duskmap", version}};
  const std::string text = manifest->configuration.dump();
  manifest->configuration_checksum = Checksum64Hex(text.data(), text.size());
}

namespace {

std::string ShortDump(const nlohmann::json& j) {
  std::string text = j.dump();
  return text.size() > 60 ? text.substr(0, 57) + "..." : text;
}

// `path` names where `earlier` and `now` sit ("" at the top).
std::string DifferenceAt(const std::string& path, const nlohmann::json& earlier,
                         const nlohmann::json& now) {
  const auto join = [&path](const std::string& key) { return path.empty() ? key : path + "." + key; };
  if (earlier.is_object() && now.is_object()) {
    std::set<std::string> keys;
    for (auto it = earlier.begin(); it != earlier.end(); ++it) keys.insert(it.key());
    for (auto it = now.begin(); it != now.end(); ++it) keys.insert(it.key());
    for (const std::string& key : keys) {
      if (!earlier.contains(key)) return join(key) + " (absent earlier, now " + ShortDump(now.at(key)) + ")";
      if (!now.contains(key)) return join(key) + " (earlier " + ShortDump(earlier.at(key)) + ", now absent)";
      const std::string inner = DifferenceAt(join(key), earlier.at(key), now.at(key));
      if (!inner.empty()) return inner;
    }
    return "";
  }
  if (earlier.is_array() && now.is_array() && earlier.size() == now.size()) {
    for (size_t i = 0; i < earlier.size(); ++i) {
      const std::string inner =
          DifferenceAt(path + "[" + std::to_string(i) + "]", earlier[i], now[i]);
      if (!inner.empty()) return inner;
    }
    return "";
  }
  if (earlier == now) return "";
  return (path.empty() ? std::string("the top level") : path) + " (earlier " + ShortDump(earlier) +
         ", now " + ShortDump(now) + ")";
}

// What changed, in words, when the first difference lies in the data rather
// than in a setting: a session's files (the dataset identity's content
// checksums) or a model or h5 file; "" otherwise.
std::string ChangedData(const std::string& difference) {
  const auto starts = [&difference](const std::string& prefix) {
    return difference.rfind(prefix, 0) == 0;
  };
  const std::string session_prefix = "dataset.content.sessions.";
  if (starts(session_prefix)) {
    const size_t end = difference.find(" (", session_prefix.size());
    return "the files of session " +
           difference.substr(session_prefix.size(), end - session_prefix.size()) +
           " (images, depth maps or metadata) changed";
  }
  if (starts("dataset.content.shared")) {
    return "the dataset's files that no one session owns (such as manifest.json) changed";
  }
  const std::string file_prefix = "feature_files.";
  if (starts(file_prefix)) {
    const size_t end = difference.find(" (", file_prefix.size());
    return "the feature file " + difference.substr(file_prefix.size(), end - file_prefix.size()) +
           " changed";
  }
  return "";
}

}  // namespace

std::string FirstJsonDifference(const nlohmann::json& earlier, const nlohmann::json& now) {
  return DifferenceAt("", earlier, now);
}

void CheckResumable(const RunManifest& earlier, const RunManifest& now, const fs::path& results_dir) {
  const std::string path = (results_dir / kManifestFile).string();
  SLAM_THROW_IF_NOT(ConfigError, earlier.features == now.features &&
                                     earlier.session_clock == now.session_clock &&
                                     earlier.shard_index == now.shard_index &&
                                     earlier.shard_count == now.shard_count)
      << path << ": an earlier run with other features, sessions or shard; cannot resume it";
  SLAM_THROW_IF_NOT(ConfigError, !earlier.configuration.is_null())
      << path << ": written by an older duskmap without a configuration record; its results "
                 "cannot be checked against this run's, so it cannot be resumed (--overwrite redoes it)";
  if (earlier.configuration_checksum == now.configuration_checksum) return;
  std::string difference = FirstJsonDifference(earlier.configuration, now.configuration);
  if (difference.empty()) difference = "the recorded checksum";
  const std::string changed = ChangedData(difference);
  SLAM_THROW_IF_NOT(ConfigError, changed.empty())
      << path << ": " << changed << " since the earlier run (first at " << difference
      << "); resuming would mix results from the old and new data (--overwrite redoes it)";
  SLAM_THROW(ConfigError) << path << ": the earlier run had another configuration, first at "
                          << difference << "; resuming would mix results (--overwrite redoes it)";
}

ExperimentPlan PlanFromManifest(ExperimentOptions options, const RunManifest& manifest) {
  options.features = manifest.features;
  return PlanExperiment(options, manifest.session_clock);
}

}  // namespace duskmap
