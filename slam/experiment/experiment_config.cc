#include "slam/experiment/experiment_config.h"

#include <filesystem>
#include <set>

#include "slam/core/check.h"
#include "slam/core/json_fields.h"
#include "slam/experiment/job_plan.h"
#include "slam/io/output_safety.h"

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
  // Map labels and session names become folder names of the results.
  std::set<std::string> map_labels;
  for (const MapSpec& map : maps) {
    CheckPathLabel(map.label, "maps");
    SLAM_THROW_IF_NOT(ConfigError, map_labels.insert(map.label).second)
        << "maps: '" << map.label << "' listed twice";
  }
  std::set<std::string> localized;
  for (const std::string& session : localization_sessions) {
    CheckPathLabel(session, "localization_sessions");
    SLAM_THROW_IF_NOT(ConfigError, localized.insert(session).second)
        << "localization_sessions: '" << session << "' listed twice";
    for (const MapSpec& map : maps) {
      for (const std::string& mapped : map.sessions) {
        SLAM_THROW_IF_NOT(ConfigError, mapped != session)
            << "localization_sessions: '" << session << "' is also a session of map '"
            << map.label << "' (a map is not re-localized on its own frames)";
      }
    }
  }
  std::set<std::pair<std::string, std::string>> pairs;
  for (const ConsecutivePair& pair : consecutive_pairs) {
    CheckPathLabel(pair.map_session, "consecutive.pairs");
    CheckPathLabel(pair.localization_session, "consecutive.pairs");
    SLAM_THROW_IF_NOT(ConfigError, pair.map_session != pair.localization_session)
        << "consecutive.pairs: session '" << pair.map_session << "' paired with itself";
    SLAM_THROW_IF_NOT(ConfigError,
                      pairs.insert({pair.map_session, pair.localization_session}).second)
        << "consecutive.pairs: [\"" << pair.map_session << "\", \"" << pair.localization_session
        << "\"] listed twice";
  }
  SLAM_THROW_IF_NOT(ConfigError, !consecutive_gap_classes_min.empty())
      << "consecutive.gap_classes_min: must not be empty";
  for (size_t i = 0; i < consecutive_gap_classes_min.size(); ++i) {
    SLAM_THROW_IF_NOT(ConfigError, consecutive_gap_classes_min[i] > 0 &&
                                       consecutive_gap_classes_min[i] <= 24 * 60 &&
                                       (i == 0 || consecutive_gap_classes_min[i] >
                                                      consecutive_gap_classes_min[i - 1]))
        << "consecutive.gap_classes_min: minutes must be increasing, in (0, 1440], got "
        << consecutive_gap_classes_min[i];
  }
  SLAM_THROW_IF_NOT(ConfigError, frame_step >= 1)
      << "frame_step: must be >= 1, got " << frame_step;
  SLAM_THROW_IF_NOT(ConfigError, max_frames_per_session >= 0)
      << "max_frames_per_session: must be >= 0, got " << max_frames_per_session;
  for (const auto& [session, hh_mm] : session_clock_times) {
    CheckPathLabel(session, "session_clock_times");
    try {
      ParseClockMinutes(hh_mm);
    } catch (const ConfigError& e) {
      SLAM_THROW(ConfigError) << "session_clock_times." << session << ": " << e.what();
    }
  }
}

void CheckSessionsExist(const ExperimentOptions& options, const std::vector<std::string>& dataset_sessions,
                        const std::string& where) {
  const std::set<std::string> known(dataset_sessions.begin(), dataset_sessions.end());
  std::string listed;
  for (const std::string& name : dataset_sessions) listed += (listed.empty() ? "" : " ") + name;
  const auto check = [&](const std::string& session, const std::string& key) {
    SLAM_THROW_IF_NOT(ConfigError, known.count(session) > 0)
        << where << ": " << key << ": session '" << session << "' is not in the dataset "
        << options.dataset_path << " (it has: " << listed << ")";
  };
  for (const MapSpec& map : options.maps) {
    for (const std::string& session : map.sessions) check(session, "maps '" + map.label + "'");
  }
  for (const std::string& session : options.localization_sessions) {
    check(session, "localization_sessions");
  }
  for (const ConsecutivePair& pair : options.consecutive_pairs) {
    check(pair.map_session, "consecutive.pairs");
    check(pair.localization_session, "consecutive.pairs");
  }
  for (const auto& [session, hh_mm] : options.session_clock_times) {
    check(session, "session_clock_times");
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
