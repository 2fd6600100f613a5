#include "slam/experiment/run_manifest.h"

#include <fstream>

#include <nlohmann/json.hpp>

#include "slam/core/check.h"

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
    const FeatureSetup& setup = FeatureSetupByLabel(label);
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
                               {"shard", {{"index", m.shard_index}, {"count", m.shard_count}}}};
  std::error_code error;
  fs::create_directories(results_dir, error);
  const fs::path path = results_dir / kManifestFile;
  const fs::path partial = path.string() + ".partial";
  {
    std::ofstream out(partial);
    out << json.dump(2) << "\n";
    SLAM_THROW_IF_NOT(InputError, out.good()) << partial.string() << ": cannot write";
  }
  fs::rename(partial, path, error);
  SLAM_THROW_IF_NOT(InputError, !error) << path.string() << ": cannot write (" << error.message()
                                        << ")";
}

RunManifest ReadRunManifest(const fs::path& results_dir) {
  const fs::path path = results_dir / kManifestFile;
  std::ifstream in(path);
  SLAM_THROW_IF_NOT(InputError, in.good())
      << path.string() << ": missing (not the results folder of `duskmap run`)";
  RunManifest m;
  try {
    const nlohmann::json json = nlohmann::json::parse(in);
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
  } catch (const nlohmann::json::exception& e) {
    SLAM_THROW(InputError) << path.string() << ": malformed run manifest (" << e.what() << ")";
  }
  return m;
}

ExperimentPlan PlanFromManifest(ExperimentOptions options, const RunManifest& manifest) {
  options.features = manifest.features;
  return PlanExperiment(options, manifest.session_clock);
}

}  // namespace duskmap
