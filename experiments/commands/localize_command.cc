// `duskmap localize`: re-localizes one session against a saved map (read
// only) and writes per-frame records, the corrected trajectory and a summary.
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <utility>

#include "experiments/command_registry.h"
#include "slam/core/check.h"
#include "slam/datasets/dataset_factory.h"
#include "slam/engine/record_io.h"
#include "slam/engine/session_runs.h"
#include "slam/map/map_memory.h"
#include "slam/map/map_store.h"

namespace duskmap::cli {
namespace {

struct LocalizeArgs {
  std::string map;
  std::string dataset;
  std::string format = "auto";
  std::string session;
  std::string config;
  std::string records;
  std::string trajectory;
  std::string summary;
  int odometry_cache = -1;
};

void WriteRecords(const std::string& path, const std::vector<LocalizationRecord>& records) {
  std::vector<nlohmann::json> rows;
  for (const auto& r : records) rows.push_back(LocalizationRecordToJson(r));
  std::ofstream out(path);
  SLAM_THROW_IF_NOT(InputError, out.good()) << path << ": cannot write";
  if (path.size() > 4 && path.substr(path.size() - 4) == ".csv") {
    WriteCsv(out, rows);
  } else {
    WriteJsonLines(out, rows);
  }
}

nlohmann::json SummaryToJson(const LocalizationRun& run) {
  const RelocalizationSummary& r = run.summary.relocalization;
  nlohmann::json j = {{"frames", r.num_frames},
                      {"relocalized", r.num_relocalized},
                      {"relocalized_pct", r.relocalized_pct},
                      {"evaluated", run.summary.evaluated},
                      {"correct", r.num_correct},
                      {"wrong", r.num_wrong},
                      {"within_0.25m_2deg", r.num_within[0]},
                      {"within_0.5m_5deg", r.num_within[1]},
                      {"within_5m_10deg", r.num_within[2]},
                      {"mean_inliers", run.summary.mean_inliers},
                      {"mean_jump_mm", run.summary.mean_jump_mm},
                      {"max_gap_m", run.summary.gaps.max_gap_m},
                      {"within_55cm_pct", run.summary.gaps.within_pct},
                      {"wall_s", run.wall_s},
                      {"peak_rss_bytes", PeakResidentBytes()},
                      {"memory_bytes", MapMemoryToJson(run.memory)}};
  for (const auto& [stage, t] : run.timings) {
    j["timings"][stage] = {{"median_ms", t.median_ms}, {"mean_ms", t.mean_ms}, {"max_ms", t.max_ms}};
  }
  return j;
}

RunFn SetupLocalize(CLI::App& command) {
  auto args = std::make_shared<LocalizeArgs>();
  command.add_option("--map", args->map, "map file (from duskmap map)")->required();
  command.add_option("--dataset", args->dataset, "dataset folder")->required();
  command.add_option("--dataset-format,--format", args->format,
                     "dataset format: auto (default), synthetic, tum, rtabmap-images, rtabmap-db");
  command.add_option("--session", args->session, "session to localize")->required();
  command.add_option("--config", args->config, "engine options (JSON); the map's feature type wins");
  command.add_option("--records", args->records, "per-frame records (.jsonl or .csv)");
  command.add_option("--trajectory", args->trajectory, "corrected trajectory (TUM format)");
  command.add_option("--summary", args->summary, "write the summary as JSON here");
  command.add_option("--odometry-cache", args->odometry_cache,
                     "odometry-cache size (0 = paper-era rule; overrides the config)");
  return [args] {
    EngineOptions options = args->config.empty() ? EngineOptions() : ReadEngineOptionsFile(args->config);
    if (args->odometry_cache >= 0) options.localization.odometry_cache_size = args->odometry_cache;
    // The words apart: the localizer imports them into its vocabulary and
    // lets them go, so the run holds them once.
    MapAndWords loaded = LoadMapAndWords(args->map, options.LocalizationMapLoad());
    const Map& map = loaded.map;
    if (args->config.empty()) options.features.type = map.metadata().feature_type;
    options.Check();
    const auto dataset = OpenDataset(args->dataset, args->format);
    std::unique_ptr<SessionReader> session = dataset->OpenSession(args->session);
    const LocalizationRun run =
        LocalizeSession(map, std::move(loaded.words), *session, options);
    if (!args->records.empty()) WriteRecords(args->records, run.records);
    if (!args->trajectory.empty()) WriteCorrectedTrajectory(args->trajectory, run.records);
    const nlohmann::json summary = SummaryToJson(run);
    if (!args->summary.empty()) {
      std::ofstream out(args->summary);
      SLAM_THROW_IF_NOT(InputError, out.good()) << args->summary << ": cannot write";
      out << summary.dump(2) << '\n';
    }
    std::cout << summary.dump(2) << '\n';
    return 0;
  };
}

const bool kRegistered = RegisterCommand(
    {"localize", "Re-localize one session against a saved map (read-only)", &SetupLocalize});

}  // namespace
}  // namespace duskmap::cli
