#include "slam/experiment/experiment_config.h"

#include <filesystem>
#include <set>

#include "slam/core/check.h"
#include "slam/core/json_fields.h"
#include "slam/experiment/job_plan.h"

namespace duskmap {
namespace {

std::string ResolveRelative(const std::string& path, const std::filesystem::path& base) {
  if (path.empty() || std::filesystem::path(path).is_absolute()) return path;
  return (base / path).lexically_normal().string();
}

std::vector<ConsecutivePair> ReadPairs(const nlohmann::json& json, const std::string& where) {
  std::vector<ConsecutivePair> pairs;
  SLAM_THROW_IF_NOT(ConfigError, json.is_array()) << where << ": expected an array of pairs";
  for (const auto& item : json) {
    SLAM_THROW_IF_NOT(ConfigError, item.is_array() && item.size() == 2 && item[0].is_string() &&
                                       item[1].is_string())
        << where << ": each pair must be [\"map session\", \"localization session\"]";
    pairs.push_back({item[0].get<std::string>(), item[1].get<std::string>()});
  }
  return pairs;
}

}  // namespace

const std::vector<FeatureSetup>& KnownFeatureSetups() {
  static const std::vector<FeatureSetup> setups = {
      {"SU", "surf", "nndr", false},        {"SI", "sift", "nndr", false},
      {"BF", "brief", "nndr", false},       {"BK", "brisk", "nndr", false},
      {"KA", "kaze", "nndr", false},        {"DY", "daisy", "nndr", false},
      {"SP", "superpoint", "nndr", true},   {"SG", "superpoint", "superglue", true},
      {"OR", "orb", "nndr", false},         {"AK", "akaze", "nndr", false},
      {"FR", "freak", "nndr", false},
  };
  return setups;
}

const FeatureSetup& FeatureSetupByLabel(const std::string& label) {
  for (const FeatureSetup& setup : KnownFeatureSetups()) {
    if (setup.label == label) return setup;
  }
  std::string known;
  for (const FeatureSetup& setup : KnownFeatureSetups()) known += " " + setup.label;
  throw ConfigError("unknown feature '" + label + "' (known:" + known + ")");
}

void ExperimentOptions::Check() const {
  SLAM_THROW_IF_NOT(ConfigError, !dataset_path.empty()) << "dataset.path: must be set";
  SLAM_THROW_IF_NOT(ConfigError, !features.empty()) << "features: at least one feature needed";
  std::set<std::string> seen;
  for (const std::string& feature : features) {
    FeatureSetupByLabel(feature);
    SLAM_THROW_IF_NOT(ConfigError, seen.insert(feature).second)
        << "features: '" << feature << "' listed twice";
  }
  SLAM_THROW_IF_NOT(ConfigError, !maps.empty() || !consecutive_pairs.empty())
      << "maps: no map and no consecutive pair: nothing to run";
  SLAM_THROW_IF_NOT(ConfigError, maps.empty() || !localization_sessions.empty())
      << "localization_sessions: maps are listed but no session localizes on them";
  for (const ConsecutivePair& pair : consecutive_pairs) {
    SLAM_THROW_IF_NOT(ConfigError, pair.map_session != pair.localization_session)
        << "consecutive.pairs: session '" << pair.map_session << "' paired with itself";
  }
  SLAM_THROW_IF_NOT(ConfigError, !consecutive_gap_classes_min.empty())
      << "consecutive.gap_classes_min: must not be empty";
  SLAM_THROW_IF_NOT(ConfigError, frame_step >= 1)
      << "frame_step: must be >= 1, got " << frame_step;
  SLAM_THROW_IF_NOT(ConfigError, max_frames_per_session >= 0)
      << "max_frames_per_session: must be >= 0, got " << max_frames_per_session;
  for (const auto& [session, hh_mm] : session_clock_times) {
    try {
      ParseClockMinutes(hh_mm);
    } catch (const ConfigError& e) {
      SLAM_THROW(ConfigError) << "session_clock_times." << session << ": " << e.what();
    }
  }
}

ExperimentOptions ReadExperimentOptions(const std::string& path) {
  const std::filesystem::path base = std::filesystem::path(path).parent_path();
  JsonFields root(ReadJsonFile(path), path);
  ExperimentOptions options;

  JsonFields dataset = root.Child("dataset");
  dataset.ReadRequired("path", &options.dataset_path);
  dataset.Read("format", &options.dataset_format);
  dataset.RejectUnknown();
  options.dataset_path = ResolveRelative(options.dataset_path, base);

  root.ReadRequired("features", &options.features);
  std::vector<std::string> map_labels;
  root.Read("maps", &map_labels);
  for (const std::string& label : map_labels) {
    try {
      options.maps.push_back(ParseMapSpec(label));
    } catch (const ConfigError& e) {
      SLAM_THROW(ConfigError) << path << ": maps: " << e.what();
    }
  }
  root.Read("localization_sessions", &options.localization_sessions);

  JsonFields consecutive = root.Child("consecutive");
  if (consecutive.Has("pairs")) {
    options.consecutive_pairs = ReadPairs(consecutive.Raw("pairs"), consecutive.where() + ".pairs");
  }
  consecutive.Read("gap_classes_min", &options.consecutive_gap_classes_min);
  consecutive.RejectUnknown();

  root.Read("engine_config", &options.engine_config);
  options.engine_config = ResolveRelative(options.engine_config, base);
  root.Read("frame_step", &options.frame_step);
  root.Read("max_frames_per_session", &options.max_frames_per_session);
  root.Read("session_clock_times", &options.session_clock_times);
  root.RejectUnknown();
  try {
    options.Check();
  } catch (const ConfigError& e) {
    SLAM_THROW(ConfigError) << path << ": " << e.what();
  }
  return options;
}

}  // namespace duskmap
