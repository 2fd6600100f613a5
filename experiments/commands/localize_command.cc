// `duskmap localize`: re-localizes one or more sessions against a saved map
// (read only, loaded once) and writes per-frame records, the corrected
// trajectory and a summary for each. Every session gets a fresh localizer
// over the one loaded map, so its results do not depend on the others.
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <set>
#include <string>
#include <utility>

#include "experiments/command_registry.h"
#include "slam/core/check.h"
#include "slam/core/timer.h"
#include "slam/datasets/dataset_factory.h"
#include "slam/engine/record_io.h"
#include "slam/engine/session_runs.h"
#include "slam/engine/session_runs_json.h"
#include "slam/experiment/job_results.h"
#include "slam/experiment/job_results_json.h"
#include "slam/features/feature_options_json.h"
#include "slam/io/output_safety.h"
#include "slam/map/map_memory.h"
#include "slam/map/map_store.h"

namespace duskmap::cli {
namespace {

struct LocalizeArgs {
  std::string map;
  std::string dataset;
  std::string format = "auto";
  std::vector<std::string> sessions;
  std::string config;
  std::string records;
  std::string trajectory;
  std::string summary;
  int odometry_cache = -1;
  bool allow_unordered = false;
};

void WriteRecords(const std::string& path, const std::vector<LocalizationRecord>& records) {
  std::vector<nlohmann::json> rows;
  for (const auto& r : records) rows.push_back(LocalizationRecordToJson(r));
  WriteFileAtomically(path, [&](std::ostream& out) {
    if (path.size() > 4 && path.substr(path.size() - 4) == ".csv") {
      WriteCsv(out, rows);
    } else {
      WriteJsonLines(out, rows);
    }
  });
}

// What `duskmap localize` prints and writes with --summary for one session:
// the summary of a localize job of `duskmap run` (LocalizationJobSummary,
// the same keys) and what only a command run has.
struct LocalizeCommandSummary {
  std::string session;
  LocalizationJobSummary job;
  double wall_s = 0.0;
  size_t peak_rss_bytes = 0;     // of the process, so far
  SessionStageTimings timings;  // median, mean and max of every stage
};

}  // namespace
}  // namespace duskmap::cli

namespace duskmap {

template <>
struct JsonCodec<cli::LocalizeCommandSummary> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    f("session", o.session);
    JsonCodec<LocalizationJobSummary>::Visit(f, o.job);  // its keys, not nested
    f("wall_s", o.wall_s);
    f("peak_rss_bytes", o.peak_rss_bytes);
    f("timings", o.timings);
  }
};

}  // namespace duskmap

namespace duskmap::cli {
namespace {

// The map was loaded before the first session: the others had it loaded.
LocalizeCommandSummary Summarize(const Map& map, const std::string& session,
                                 const LocalizationRun& run, bool first, double map_load_s) {
  LocalizeCommandSummary summary;
  summary.session = session;
  summary.job = SummarizeLocalization(map, run);
  summary.job.map_load_s = first ? map_load_s : 0.0;
  summary.job.map_from_cache = !first;
  summary.wall_s = run.wall_s;
  summary.peak_rss_bytes = PeakResidentBytes();
  summary.timings = run.timings;
  return summary;
}

// The path for one session: `path` itself with a single session, else with
// "{session}" replaced by the session name.
std::string SessionPath(const std::string& path, const std::string& session, bool several) {
  if (!several || path.empty()) return path;
  std::string out = path;
  const std::string key = "{session}";
  for (size_t at = out.find(key); at != std::string::npos; at = out.find(key, at + session.size())) {
    out.replace(at, key.size(), session);
  }
  return out;
}

void CheckSessionPaths(const LocalizeArgs& args) {
  std::set<std::string> seen;
  for (const std::string& s : args.sessions) {
    SLAM_THROW_IF_NOT(ConfigError, seen.insert(s).second)
        << "localize: session '" << s << "' is given twice";
  }
  if (args.sessions.size() >= 2) {
    for (const auto& [flag, path] :
         {std::pair<const char*, const std::string&>{"--records", args.records},
          {"--trajectory", args.trajectory},
          {"--summary", args.summary}}) {
      SLAM_THROW_IF_NOT(ConfigError, path.empty() || path.find("{session}") != std::string::npos)
          << "localize: " << flag << " " << path
          << ": with several sessions the path must contain {session}";
    }
  }
  SLAM_THROW_IF_NOT(ConfigError, args.odometry_cache >= -1 && args.odometry_cache <= 100000)
      << "localize: --odometry-cache: must be in [0, 100000], got " << args.odometry_cache;
  // Every output of every session, apart from the inputs and from each other.
  std::vector<NamedPath> outputs;
  for (const std::string& s : args.sessions) {
    for (const auto& [flag, path] : {std::pair<const char*, const std::string&>{"--records", args.records},
                                     {"--trajectory", args.trajectory},
                                     {"--summary", args.summary}}) {
      outputs.push_back({flag, SessionPath(path, s, args.sessions.size() > 1)});
    }
  }
  CheckOutputsApartFromInputs(outputs, {{"--map", args.map},
                                        {"--dataset", args.dataset},
                                        {"--config", args.config}});
}

// The engine options: the config (or the defaults) with --odometry-cache.
EngineOptions LocalizeOptions(const LocalizeArgs& args) {
  EngineOptions options = args.config.empty() ? EngineOptions() : ReadEngineOptionsFile(args.config);
  if (args.odometry_cache >= 0) options.localization.odometry_cache_size = args.odometry_cache;
  return options;
}

// The map's feature type wins: its descriptors decide what can match.
void UseMapFeatures(const LocalizeArgs& args, const Map& map, EngineOptions* options) {
  if (!args.config.empty() && options->features.type != map.metadata().feature_type) {
    std::cerr << "duskmap localize: note: " << args.config << ": features.type '"
              << options->features.type << "' ignored; the map " << args.map
              << " was built with '" << map.metadata().feature_type << "'\n";
  }
  options->features.type = map.metadata().feature_type;
  if (args.config.empty()) {  // every feature option as the map was built (h5 file, onnx model, ...)
    options->features = FeatureOptionsOfMap(map.metadata().feature_parameters_json, args.map);
  }
  options->Check();
}

// One session's records, trajectory and --summary file; returns its summary.
nlohmann::json WriteSessionOutputs(const LocalizeArgs& args, const Map& map, size_t index,
                                   const LocalizationRun& run, double map_load_s) {
  const std::string& name = args.sessions[index];
  const bool several = args.sessions.size() > 1;
  const std::string records = SessionPath(args.records, name, several);
  const std::string trajectory = SessionPath(args.trajectory, name, several);
  const std::string summary_path = SessionPath(args.summary, name, several);
  if (!records.empty()) WriteRecords(records, run.records);
  if (!trajectory.empty()) WriteCorrectedTrajectory(trajectory, run.records);
  nlohmann::json summary = ToJsonObject(Summarize(map, name, run, index == 0, map_load_s));
  if (!summary_path.empty()) {
    WriteFileAtomically(summary_path, [&](std::ostream& out) { out << summary.dump(2) << '\n'; });
  }
  return summary;
}

int RunLocalize(const LocalizeArgs& args) {
  CheckSessionPaths(args);
  EngineOptions options = LocalizeOptions(args);
  // The words apart: each session's localizer imports a copy into its
  // vocabulary and lets it go.
  Stopwatch load;
  MapAndWords loaded = LoadMapAndWords(args.map, options.LocalizationMapLoad());
  const double map_load_s = load.ElapsedMs() / 1000.0;
  const Map& map = loaded.map;
  UseMapFeatures(args, map, &options);
  DatasetReadOptions read;
  read.allow_unordered = args.allow_unordered;
  const auto dataset = OpenDataset(args.dataset, args.format, read);
  // Every session is opened before the first is localized: a wrong name
  // fails before any work.
  std::vector<std::unique_ptr<SessionReader>> readers;
  for (const std::string& name : args.sessions) readers.push_back(dataset->OpenSession(name));
  nlohmann::json summaries = nlohmann::json::array();
  bool warned = false;
  for (size_t i = 0; i < readers.size(); ++i) {
    const bool last = i + 1 == readers.size();
    const LocalizationRun run = LocalizeSession(
        map, last ? std::move(loaded.words) : MapWords(loaded.words), *readers[i], options);
    readers[i].reset();
    // (A map without words has no index to restore or rebuild.)
    if (!run.index_restore.restored && !run.index_restore.rebuild_reason.empty() && !warned) {
      std::cerr << "duskmap localize: warning: " << args.map
                << ": vocabulary index rebuilt (" << run.index_restore.rebuild_reason << ", "
                << run.index_restore.seconds << " s); the map is unchanged\n";
      warned = true;
    }
    summaries.push_back(WriteSessionOutputs(args, map, i, run, map_load_s));
  }
  // stdout leaves out the one-entry-per-frame list (the --summary file has it).
  for (nlohmann::json& summary : summaries) summary.erase("matched_session_per_frame");
  std::cout << (args.sessions.size() > 1 ? summaries : summaries[0]).dump(2) << '\n';
  return 0;
}

RunFn SetupLocalize(CLI::App& command) {
  auto args = std::make_shared<LocalizeArgs>();
  command.add_option("--map", args->map, "map file (from duskmap map)")->required();
  command.add_option("--dataset", args->dataset, "dataset folder")->required();
  command.add_option("--dataset-format,--format", args->format,
                     "dataset format: auto (default), synthetic, tum, rtabmap-images, rtabmap-db");
  command.add_option("--session", args->sessions,
                     "session(s) to localize, each against the same loaded map")
      ->required();
  command.add_option("--config", args->config,
                     "engine options (JSON); the map's feature type wins. Without it, the "
                     "features are made as the map's were (its stored feature options)");
  command.add_option("--records", args->records,
                     "per-frame records (.jsonl or .csv); with several sessions the path "
                     "must contain {session}");
  command.add_option("--trajectory", args->trajectory,
                     "corrected trajectory (TUM format); {session} as for --records");
  command.add_option("--summary", args->summary,
                     "write the summary as JSON here; {session} as for --records");
  command.add_flag("--allow-unordered", args->allow_unordered,
                   "read rgb.txt/depth.txt as recorded: sort them and drop unmatched frames (real TUM recordings)");
  command.add_option("--odometry-cache", args->odometry_cache,
                     "odometry-cache size (0 = paper-era rule; overrides the config)");
  return [args] { return RunLocalize(*args); };
}

const bool kRegistered = RegisterCommand(
    {"localize", "Re-localize one or more sessions against a saved map (read-only, loaded once)",
     &SetupLocalize});

}  // namespace
}  // namespace duskmap::cli
