// What one experiment run covers: the dataset, the feature types, the maps,
// the localization sessions and the consecutive-session pairs. Read from a
// JSON file under configs/ (unknown keys are rejected).
#pragma once

#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "slam/experiment/map_spec.h"
#include "slam/features/feature_options.h"

namespace duskmap {

// A feature column of the paper's tables: which extractor and which matcher.
// The built-in columns are the registry's (features/feature_registry.h).
struct FeatureSetup {
  std::string label;      // column code, as in the paper: SU, SI, ..., SG
  std::string extractor;  // the feature type's name (FeatureType::name)
  std::string matcher;    // MatcherOptions::type: nndr or superglue
  // The column's type reads a model that the engine config names
  // (SuperPoint's, for SP and SG: FeatureType::file).
  bool needs_model = false;
  // A column the experiment config declares: features imported from a file
  // in hloc's layout (extractor "h5") or detected by an ONNX model with its
  // declared contract (extractor "onnx"); unused by the built-in columns.
  H5FeatureOptions h5;
  OnnxFeatureOptions onnx;

  // The name of the column's extract jobs and feature caches: the extractor
  // for built-in columns (SP and SG share SuperPoint's), "<extractor>-<label>"
  // for a declared one (two declared columns never share a cache).
  std::string CacheName() const;
  // A column the experiment config declares (of a type with no built-in column).
  bool IsDeclared() const;
  // Sets the column's extractor (and a declared column's file or model
  // options) on `features`, whose other options stay.
  void ApplyTo(FeatureOptions* features) const;
};

// The known feature columns (paper's eight plus ORB, AKAZE, FREAK): every
// column of the feature registry, in its order.
const std::vector<FeatureSetup>& KnownFeatureSetups();
// Throws ConfigError when label is unknown.
const FeatureSetup& FeatureSetupByLabel(const std::string& label);

struct ConsecutivePair {
  std::string map_session;           // the earlier mapping session (the map)
  std::string localization_session;  // the later mapping session replayed against it
};

// The scaling curve of the report (issue 46): maps of growing size, each one
// of the config's own maps, in the curve's order ("1", "1-2", "1-2-3", ...).
// It adds no job: the report lays out what the maps' jobs measured (nodes,
// LCD + TE per frame, memory, map open time, re-localization) against the
// number of sessions in each map.
struct ScalingCurve {
  std::vector<std::string> maps;  // map labels, at least 2, listed once, none "closest in time"
};

struct ExperimentOptions {
  std::string dataset_path;            // dataset folder or file
  std::string dataset_format = "auto"; // synthetic | tum | rtabmap-images | rtabmap-db | auto
  std::vector<std::string> features;   // FeatureSetup labels, e.g. {"SU", "SI", "MY"}
  // Columns the config declares beside the known ones, e.g.
  //   {"code": "MY", "type": "h5", "path": "feats/disk.h5", "descriptor_kind": "float"}
  //   {"code": "XF", "type": "onnx", "model_path": "models/xfeat.onnx", ...}
  // (an onnx column's other keys are features.onnx's: feature_options.h)
  std::vector<FeatureSetup> declared_features;
  std::vector<MapSpec> maps;
  std::vector<std::string> localization_sessions;
  std::vector<ConsecutivePair> consecutive_pairs;
  std::vector<int> consecutive_gap_classes_min = {30, 60, 120};
  std::string engine_config;  // JSON with the engine's options; empty = paper defaults
  int frame_step = 1;         // use every frame_step-th frame (quick profiles)
  int max_frames_per_session = 0;  // 0 = all frames
  // Local clock time ("HH:MM") per session name, for readers that do not
  // store one (RTAB-Map databases and image releases) or to override the
  // dataset's: the "closest in time" map (1|2|...|6) and the consecutive
  // pairs' gap classes need them.
  std::map<std::string, std::string> session_clock_times;
  // "scaling": {"maps": [...]}; absent = no scaling section in the report.
  std::optional<ScalingCurve> scaling;

  // Throws ConfigError naming the field.
  void Check() const;
  // The setup of column `label` (declared, else known); throws ConfigError.
  const FeatureSetup& FeatureSetupOf(const std::string& label) const;
};

// Reads and checks an experiment config; relative paths inside it are resolved
// against the config file's folder. Throws ConfigError("<file>...: <problem>").
ExperimentOptions ReadExperimentOptions(const std::string& path);

// Opens the file (or checks the folder) of every declared h5 column and loads
// and checks the model of every declared onnx column, so that a missing or
// foreign file fails before any job runs: InputError naming it.
void CheckDeclaredFeatureFiles(const ExperimentOptions& options);

// Throws ConfigError("<where>: <key>: session 'Z' is not in the dataset ...")
// when a map, localization session, consecutive pair or clock time names a
// session the dataset lacks: checked before any job runs.
void CheckSessionsExist(const ExperimentOptions& options,
                        const std::vector<std::string>& dataset_sessions, const std::string& where);

}  // namespace duskmap
