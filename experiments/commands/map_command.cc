// `duskmap map`: replays one or more sessions back to back into one map,
// saves it (SQLite) and prints/writes the map summary.
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <set>

#include "experiments/command_registry.h"
#include "slam/core/check.h"
#include "slam/datasets/dataset_factory.h"
#include "slam/engine/record_io.h"
#include "slam/engine/session_runs.h"
#include "slam/engine/session_runs_json.h"
#include "slam/io/output_safety.h"
#include "slam/map/map_memory.h"
#include "slam/map/map_store.h"

namespace duskmap::cli {
namespace {

struct MapArgs {
  std::string dataset;
  std::string format = "auto";
  std::vector<std::string> sessions;
  std::string config;
  std::string feature;
  std::string output;
  std::string summary;
  std::string frames;
  bool reduce = false;
  bool overwrite = false;
  bool allow_unordered = false;
};

void WriteFrames(const std::string& path, const std::vector<MappingFrameResult>& frames) {
  std::vector<nlohmann::json> rows;
  for (const auto& f : frames) rows.push_back(MappingResultToJson(f));
  WriteFileAtomically(path, [&](std::ostream& out) {
    if (path.size() > 4 && path.substr(path.size() - 4) == ".csv") {
      WriteCsv(out, rows);
    } else {
      WriteJsonLines(out, rows);
    }
  });
}

// Before any work: the outputs are apart from the inputs and from each
// other, an existing map is replaced only with --overwrite and only when it
// is a duskmap map, the sessions are listed once and the feature is named.
void CheckMapArgs(const MapArgs& args, bool feature_given) {
  std::set<std::string> seen;
  for (const std::string& s : args.sessions) {
    SLAM_THROW_IF_NOT(ConfigError, !s.empty()) << "map: --sessions: empty session name";
    SLAM_THROW_IF_NOT(ConfigError, seen.insert(s).second)
        << "map: --sessions: session '" << s << "' is given twice";
  }
  SLAM_THROW_IF_NOT(ConfigError, !feature_given || !args.feature.empty())
      << "map: --feature: empty feature type";
  CheckOutputsApartFromInputs(
      {{"--output", args.output}, {"--summary", args.summary}, {"--frames", args.frames}},
      {{"--dataset", args.dataset}, {"--config", args.config}});
  CheckMayReplace({"--output", args.output}, args.overwrite,
                  {"a duskmap map", [](const std::filesystem::path& p) {
                     return IsDuskmapMapFile(p.string());
                   }});
}

RunFn SetupMap(CLI::App& command) {
  auto args = std::make_shared<MapArgs>();
  command.add_option("--dataset", args->dataset, "dataset folder")->required();
  command.add_option("--dataset-format,--format", args->format,
                     "dataset format: auto (default), synthetic, tum, rtabmap-images, rtabmap-db");
  command.add_option("--sessions", args->sessions, "sessions to replay, in order")
      ->required()->delimiter(',');
  command.add_option("--config", args->config, "engine options (JSON, configs/engine_*.json)");
  command.add_option("--feature", args->feature, "feature type (overrides the config)");
  command.add_option("--output", args->output, "map file to write (SQLite)")->required();
  command.add_option("--summary", args->summary, "write the map summary as JSON here");
  command.add_option("--frames", args->frames, "per-frame records (.jsonl or .csv)");
  command.add_flag("--reduce", args->reduce, "graph reduction (the paper's 1-2-3-4-5-6 maps)");
  command.add_flag("--allow-unordered", args->allow_unordered,
                   "read rgb.txt/depth.txt as recorded: sort them and drop unmatched frames (real TUM recordings)");
  command.add_flag("--overwrite", args->overwrite, "replace an existing map file (only a duskmap map)");
  CLI::Option* feature_option = command.get_option("--feature");
  return [args, feature_option] {
    CheckMapArgs(*args, feature_option->count() > 0);
    EngineOptions options = args->config.empty() ? EngineOptions() : ReadEngineOptionsFile(args->config);
    if (!args->feature.empty()) options.features.type = args->feature;
    if (args->reduce) options.mapping.reduce_graph = true;
    options.Check();
    DatasetReadOptions read;
    read.allow_unordered = args->allow_unordered;
    const auto dataset = OpenDataset(args->dataset, args->format, read);
    const MappingRun run = BuildMap(*dataset, args->sessions, options);
    // Checked again as it is saved: a file that appeared at --output while
    // the map was built is never replaced without --overwrite.
    MapSaveOptions save;
    save.overwrite = args->overwrite;
    save.flag = "--output";
    SaveMap(run.map, args->output, save);
    nlohmann::json summary = ToJsonObject(SummarizeMap(run.map));
    summary["frames"] = run.frames.size();
    summary["wall_s"] = run.wall_s;
    summary["index_build_s"] = run.index_build_s;
    summary["timings"] = ToJsonObject(run.timings);
    summary["peak_rss_bytes"] = PeakResidentBytes();
    summary["map_file"] = args->output;
    if (!args->frames.empty()) WriteFrames(args->frames, run.frames);
    if (!args->summary.empty()) {
      WriteFileAtomically(args->summary, [&](std::ostream& out) { out << summary.dump(2) << '\n'; });
    }
    std::cout << summary.dump(2) << '\n';
    return 0;
  };
}

const bool kRegistered = RegisterCommand(
    {"map", "Build a (multi-session) map from dataset sessions and save it", &SetupMap});

}  // namespace
}  // namespace duskmap::cli
