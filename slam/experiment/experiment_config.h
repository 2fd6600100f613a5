// What one experiment run covers: the dataset, the feature types, the maps,
// the localization sessions and the consecutive-session pairs. Read from a
// JSON file under configs/ (unknown keys are rejected).
#pragma once

#include <map>
#include <string>
#include <utility>
#include <vector>

#include "slam/experiment/map_spec.h"

namespace duskmap {

// A feature column of the paper's tables: which extractor and which matcher.
struct FeatureSetup {
  std::string label;      // column code, as in the paper: "SU", "SI", ..., "SG"
  std::string extractor;  // extractor factory name: "surf", "sift", ...
  std::string matcher;    // "nndr" or "superglue"
  bool needs_model = false;  // SuperPoint / SuperGlue need an ONNX model file
};

// The known feature columns (paper's eight plus ORB, AKAZE, FREAK).
const std::vector<FeatureSetup>& KnownFeatureSetups();
// Throws ConfigError when label is unknown.
const FeatureSetup& FeatureSetupByLabel(const std::string& label);

struct ConsecutivePair {
  std::string map_session;           // the earlier mapping session (the map)
  std::string localization_session;  // the later mapping session replayed against it
};

struct ExperimentOptions {
  std::string dataset_path;            // dataset folder or file
  std::string dataset_format = "auto"; // synthetic | tum | rtabmap-images | rtabmap-db | auto
  std::vector<std::string> features;   // FeatureSetup labels, e.g. {"SU", "SI"}
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

  // Throws ConfigError naming the field.
  void Check() const;
};

// Reads and checks an experiment config; relative paths inside it are resolved
// against the config file's folder. Throws ConfigError("<file>...: <problem>").
ExperimentOptions ReadExperimentOptions(const std::string& path);

// Throws ConfigError("<where>: <key>: session 'Z' is not in the dataset ...")
// when a map, localization session, consecutive pair or clock time names a
// session the dataset lacks: checked before any job runs.
void CheckSessionsExist(const ExperimentOptions& options,
                        const std::vector<std::string>& dataset_sessions, const std::string& where);

}  // namespace duskmap
