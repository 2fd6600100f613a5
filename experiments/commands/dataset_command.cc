// `duskmap dataset info PATH [--dataset-format F] [--skip-bad-frames]`: prints
// what a reader sees in a dataset (format, sessions, frames, resolution, depth
// range, time span, ground truth), so a download can be checked before a run.
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>

#include "experiments/command_registry.h"
#include "slam/datasets/dataset_factory.h"
#include "slam/datasets/dataset_summary.h"

namespace duskmap::cli {
namespace {

struct InfoArgs {
  std::string path;
  std::string format = "auto";
  bool skip_bad_frames = false;
  bool allow_unordered = false;
};

std::string Resolutions(const SessionSummary& s) {
  std::ostringstream text;
  for (const auto& [size, frames] : s.frames_per_resolution) {
    if (text.tellp() > 0) text << ", ";
    text << size.first << "x" << size.second;
    if (s.frames_per_resolution.size() > 1) text << " (" << frames << " frames)";
  }
  return text.str();
}

void PrintSession(const SessionSummary& s) {
  std::cout << "session " << s.info.name << "\n"
            << std::fixed << std::setprecision(3)
            << "  clock time:   " << s.info.clock_time.value_or("unknown") << "\n"
            << "  frames:       " << s.frames_read << " (listed " << s.info.num_frames << ")\n"
            << "  resolution:   " << (s.frames_read ? Resolutions(s) : "-") << "\n"
            << "  depth range:  " << s.min_depth_m << " - " << s.max_depth_m << " m ("
            << std::setprecision(1) << 100.0 * s.valid_depth_fraction << "% valid pixels)\n"
            << std::setprecision(6) << "  time span:    " << s.first_timestamp_s << " - "
            << s.last_timestamp_s << " s (" << std::setprecision(3)
            << s.last_timestamp_s - s.first_timestamp_s << " s)\n"
            << "  ground truth: "
            << (s.frames_with_ground_truth == 0                ? "no"
                : s.frames_with_ground_truth == s.frames_read ? "yes"
                                                               : "partial")
            << " (" << s.frames_with_ground_truth << " frames)\n";
}

int RunInfo(const InfoArgs& args) {
  DatasetReadOptions options;
  options.skip_bad_frames = args.skip_bad_frames;
  options.allow_unordered = args.allow_unordered;
  if (args.skip_bad_frames) options.skip_log = std::make_shared<SkipLog>();
  const std::unique_ptr<DatasetReader> reader = OpenDataset(args.path, args.format, options);
  const std::vector<SessionInfo> sessions = reader->Sessions();
  std::cout << "dataset  " << args.path << "\nformat   " << reader->format() << "\nsessions "
            << sessions.size() << "\n";
  int64_t total_frames = 0;
  for (const SessionInfo& info : sessions) {
    const std::unique_ptr<SessionReader> session = reader->OpenSession(info.name);
    const SessionSummary summary = SummarizeSession(*session);
    total_frames += summary.frames_read;
    PrintSession(summary);
  }
  std::cout << "total frames " << total_frames << "\n";
  if (options.skip_log) {
    std::cout << "skipped bad frames " << options.skip_log->count() << "\n";
    for (const std::string& message : options.skip_log->messages()) {
      std::cout << "  skipped: " << message << "\n";
    }
  }
  return 0;
}

RunFn SetupDataset(CLI::App& command) {
  command.require_subcommand(1);
  auto args = std::make_shared<InfoArgs>();
  CLI::App* info = command.add_subcommand("info", "Print what a reader sees in a dataset");
  info->add_option("path", args->path, "Dataset folder or file")->required();
  info->add_option("--dataset-format", args->format,
                   "auto, synthetic, tum, rtabmap-images or rtabmap-db")
      ->capture_default_str();
  info->add_flag("--skip-bad-frames", args->skip_bad_frames,
                 "Skip frames that cannot be read and report how many");
  info->add_flag("--allow-unordered", args->allow_unordered,
                 "Read rgb.txt/depth.txt as recorded: sort them, drop unmatched frames");
  return [args, info] {
    if (info->parsed()) return RunInfo(*args);
    return 1;
  };
}

const bool kRegistered = RegisterCommand(
    {"dataset", "Inspect datasets (synthetic, TUM, RTAB-Map images or databases)", &SetupDataset});

}  // namespace
}  // namespace duskmap::cli
