#include "slam/experiment/experiment_config.h"

#include <algorithm>
#include <filesystem>
#include <set>

#include "slam/core/check.h"
#include "slam/core/json_fields.h"
#include "slam/experiment/session_clock.h"
#include "slam/features/feature_options_json.h"
#include "slam/features/feature_factory.h"
#include "slam/features/feature_registry.h"
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

// "h5 or onnx": the types whose columns a config declares.
std::string DeclarableTypes() {
  std::string names;
  for (const FeatureType& type : FeatureTypes()) {
    if (type.DeclaredByConfig()) names += (names.empty() ? "" : " or ") + type.name;
  }
  return names;
}

// One declared column: {"code", "type", and the keys of its type's options
// (features.h5's or features.onnx's)}, with the file its type reads required
// and resolved against the config's folder.
FeatureSetup ReadDeclaredColumn(JsonFields& column, const std::filesystem::path& base) {
  const std::string& at = column.where();
  FeatureSetup setup;
  std::string type_name;
  column.ReadRequired("code", &setup.label);
  column.ReadRequired("type", &type_name);
  const FeatureType* type = FindFeatureType(type_name);
  SLAM_THROW_IF_NOT(ConfigError, type != nullptr && type->DeclaredByConfig())
      << at << ".type: '" << type_name << "' cannot be declared (a config declares columns of type "
      << DeclarableTypes() << ", which import a file or run a model; built-in types are listed by "
      << "code: " << KnownFeatureColumnCodes() << ")";
  // The column's keys are its type's options': the file's key without the
  // options' own ("h5.path": "path").
  const std::string file_key = type->file->key.substr(type->file->key.find('.') + 1);
  SLAM_THROW_IF_NOT(ConfigError, column.Has(file_key)) << at << ": missing key '" << file_key << "'";
  setup.extractor = type->name;
  setup.matcher = "nndr";
  if (type->id == FeatureTypeId::kH5) {
    JsonCodecReader::ReadFields(column, &setup.h5);
    setup.h5.path = ResolveRelative(setup.h5.path, base);
  } else {
    JsonCodecReader::ReadFields(column, &setup.onnx);
    setup.onnx.model_path = ResolveRelative(setup.onnx.model_path, base);
  }
  return setup;
}

// The "features" array: known column codes as strings, declared columns as
// objects {"code", "type": "h5", "path", "descriptor_kind", "keypoint_origin"}
// or {"code", "type": "onnx", "model_path", <other features.onnx keys>}.
void ReadFeatures(JsonFields& root, const std::filesystem::path& base, ExperimentOptions* options) {
  const nlohmann::json& features = root.Raw("features");
  const std::string where = root.where() + ".features";
  SLAM_THROW_IF_NOT(ConfigError, features.is_array())
      << where << ": expected an array of column codes (\"SU\") or declared columns ({\"code\": ...})";
  for (size_t i = 0; i < features.size(); ++i) {
    const std::string at = where + "[" + std::to_string(i) + "]";
    if (features[i].is_string()) {
      options->features.push_back(features[i].get<std::string>());
      continue;
    }
    SLAM_THROW_IF_NOT(ConfigError, features[i].is_object())
        << at << ": expected a column code or a declared column object";
    JsonFields column(features[i], at);
    const FeatureSetup setup = ReadDeclaredColumn(column, base);
    options->features.push_back(setup.label);
    options->declared_features.push_back(setup);
  }
}

}  // namespace

std::string FeatureSetup::CacheName() const {
  return IsDeclared() ? extractor + "-" + label : extractor;
}

bool FeatureSetup::IsDeclared() const {
  const FeatureType* type = FindFeatureType(extractor);
  return type != nullptr && type->DeclaredByConfig();
}

void FeatureSetup::ApplyTo(FeatureOptions* features) const {
  features->type = extractor;
  if (extractor == FeatureTypeName(FeatureTypeId::kH5)) features->h5 = h5;
  if (extractor == FeatureTypeName(FeatureTypeId::kOnnx)) features->onnx = onnx;
}

const FeatureSetup& ExperimentOptions::FeatureSetupOf(const std::string& label) const {
  for (const FeatureSetup& setup : declared_features) {
    if (setup.label == label) return setup;
  }
  return FeatureSetupByLabel(label);
}

const std::vector<FeatureSetup>& KnownFeatureSetups() {
  static const std::vector<FeatureSetup> setups = [] {
    std::vector<FeatureSetup> known;
    for (const FeatureType& type : FeatureTypes()) {
      for (const FeatureColumn& column : type.columns) {
        FeatureSetup setup;
        setup.label = column.code;
        setup.extractor = type.name;
        setup.matcher = column.matcher;
        setup.needs_model = type.file.has_value();
        known.push_back(setup);
      }
    }
    return known;
  }();
  return setups;
}

const FeatureSetup& FeatureSetupByLabel(const std::string& label) {
  for (const FeatureSetup& setup : KnownFeatureSetups()) {
    if (setup.label == label) return setup;
  }
  throw ConfigError("unknown feature '" + label + "' (known: " + KnownFeatureColumnCodes() + ")");
}

namespace {

// The columns: declared ones with codes of their own and valid options, each
// listed column known or declared, and listed once.
void CheckFeatureColumns(const ExperimentOptions& o) {
  SLAM_THROW_IF_NOT(ConfigError, !o.features.empty()) << "features: at least one feature needed";
  for (const FeatureSetup& declared : o.declared_features) {
    CheckPathLabel(declared.label, "features (declared code)");
    for (const FeatureSetup& known : KnownFeatureSetups()) {
      SLAM_THROW_IF_NOT(ConfigError, known.label != declared.label)
          << "features: declared code '" << declared.label << "' is a built-in column's ("
          << known.extractor << "); choose another code";
    }
    try {
      if (declared.extractor == FeatureTypeName(FeatureTypeId::kH5)) declared.h5.Check();
      if (declared.extractor == FeatureTypeName(FeatureTypeId::kOnnx)) declared.onnx.Check();
    } catch (const ConfigError& e) {
      SLAM_THROW(ConfigError) << "features: '" << declared.label << "': " << e.what();
    }
  }
  std::set<std::string> seen;
  for (const std::string& feature : o.features) {
    o.FeatureSetupOf(feature);
    SLAM_THROW_IF_NOT(ConfigError, seen.insert(feature).second)
        << "features: '" << feature << "' listed twice";
  }
}

// Maps and the sessions localized on them: something to run, labels usable
// as folder names, listed once, no map re-localized on its own frames.
void CheckMapsAndSessions(const ExperimentOptions& o) {
  SLAM_THROW_IF_NOT(ConfigError, !o.maps.empty() || !o.consecutive_pairs.empty())
      << "maps: no map and no consecutive pair: nothing to run";
  SLAM_THROW_IF_NOT(ConfigError, o.maps.empty() || !o.localization_sessions.empty())
      << "localization_sessions: maps are listed but no session localizes on them";
  // Map labels and session names become folder names of the results.
  std::set<std::string> map_labels;
  for (const MapSpec& map : o.maps) {
    CheckPathLabel(map.label, "maps");
    SLAM_THROW_IF_NOT(ConfigError, map_labels.insert(map.label).second)
        << "maps: '" << map.label << "' listed twice";
  }
  std::set<std::string> localized;
  for (const std::string& session : o.localization_sessions) {
    CheckPathLabel(session, "localization_sessions");
    SLAM_THROW_IF_NOT(ConfigError, localized.insert(session).second)
        << "localization_sessions: '" << session << "' listed twice";
    for (const MapSpec& map : o.maps) {
      for (const std::string& mapped : map.sessions) {
        SLAM_THROW_IF_NOT(ConfigError, mapped != session)
            << "localization_sessions: '" << session << "' is also a session of map '"
            << map.label << "' (a map is not re-localized on its own frames)";
      }
    }
  }
}

// The consecutive pairs (two sessions, listed once) and the gap classes.
void CheckConsecutive(const ExperimentOptions& o) {
  std::set<std::pair<std::string, std::string>> pairs;
  for (const ConsecutivePair& pair : o.consecutive_pairs) {
    CheckPathLabel(pair.map_session, "consecutive.pairs");
    CheckPathLabel(pair.localization_session, "consecutive.pairs");
    SLAM_THROW_IF_NOT(ConfigError, pair.map_session != pair.localization_session)
        << "consecutive.pairs: session '" << pair.map_session << "' paired with itself";
    SLAM_THROW_IF_NOT(ConfigError,
                      pairs.insert({pair.map_session, pair.localization_session}).second)
        << "consecutive.pairs: [\"" << pair.map_session << "\", \"" << pair.localization_session
        << "\"] listed twice";
  }
  const std::vector<int>& classes = o.consecutive_gap_classes_min;
  SLAM_THROW_IF_NOT(ConfigError, !classes.empty()) << "consecutive.gap_classes_min: must not be empty";
  for (size_t i = 0; i < classes.size(); ++i) {
    SLAM_THROW_IF_NOT(ConfigError, classes[i] > 0 && classes[i] <= 24 * 60 &&
                                       (i == 0 || classes[i] > classes[i - 1]))
        << "consecutive.gap_classes_min: minutes must be increasing, in (0, 1440], got "
        << classes[i];
  }
}

// The scaling curve: at least two of the config's own maps, each once.
void CheckScaling(const ExperimentOptions& o) {
  if (!o.scaling) return;
  const std::vector<std::string>& curve = o.scaling->maps;
  SLAM_THROW_IF_NOT(ConfigError, curve.size() >= 2)
      << "scaling.maps: a curve needs at least 2 maps, got " << curve.size();
  std::set<std::string> seen;
  for (const std::string& label : curve) {
    const auto map = std::find_if(o.maps.begin(), o.maps.end(),
                                  [&label](const MapSpec& m) { return m.label == label; });
    SLAM_THROW_IF_NOT(ConfigError, map != o.maps.end())
        << "scaling.maps: '" << label << "' is not one of the config's maps";
    SLAM_THROW_IF_NOT(ConfigError, map->BuildsItsOwnMap())
        << "scaling.maps: '" << label
        << "' is a closest-in-time map (no map of its own, so no size to plot)";
    SLAM_THROW_IF_NOT(ConfigError, seen.insert(label).second)
        << "scaling.maps: '" << label << "' listed twice";
  }
}

}  // namespace

void ExperimentOptions::Check() const {
  SLAM_THROW_IF_NOT(ConfigError, !dataset_path.empty()) << "dataset.path: must be set";
  CheckFeatureColumns(*this);
  CheckMapsAndSessions(*this);
  CheckConsecutive(*this);
  CheckScaling(*this);
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

void CheckDeclaredFeatureFiles(const ExperimentOptions& options) {
  for (const FeatureSetup& setup : options.declared_features) {
    FeatureOptions features;
    setup.ApplyTo(&features);
    CreateFeatureExtractor(features);  // h5 opens its file, onnx loads and checks its model
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

  SLAM_THROW_IF_NOT(ConfigError, root.Has("features")) << root.where() << ": missing key 'features'";
  ReadFeatures(root, base, &options);
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
  if (root.Has("scaling")) {
    SLAM_THROW_IF_NOT(ConfigError, root.Raw("scaling").is_object())
        << root.where() << ".scaling: expected an object {\"maps\": [map labels]}";
    JsonFields scaling = root.Child("scaling");
    options.scaling.emplace();
    scaling.Read("maps", &options.scaling->maps);
    scaling.RejectUnknown();
  }
  root.RejectUnknown();
  try {
    options.Check();
  } catch (const ConfigError& e) {
    SLAM_THROW(ConfigError) << path << ": " << e.what();
  }
  return options;
}

}  // namespace duskmap
