// `duskmap features training-data --config configs/dusknet.json --out DIR`:
// the learned descriptor's training pairs (slam/training/training_data.h),
// one progress line per scene and a summary.
#include "experiments/commands/training_data_command.h"

#include <algorithm>
#include <cstdio>
#include <memory>
#include <thread>

#include "slam/core/check.h"
#include "slam/io/output_safety.h"
#include "slam/training/training_data.h"

namespace duskmap::cli {
namespace {

struct TrainingDataArgs {
  std::string config_path;
  int threads = 0;  // used when --threads is given
  TrainingDataRunOptions run;
};

int RunTrainingData(const TrainingDataArgs& args, bool threads_given) {
  SLAM_THROW_IF_NOT(ConfigError, !threads_given || args.threads >= 1)
      << "features training-data: --threads must be >= 1, got " << args.threads;
  CheckOutputsApartFromInputs({{"--out", args.run.output_path}}, {{"--config", args.config_path}});
  SLAM_THROW_IF_NOT(InputError, !IsSameOrInside(args.config_path, args.run.output_path))
      << args.run.output_path << ": --out would replace the folder holding --config " << args.config_path
      << "; choose another output";
  TrainingDataOptions options = ReadTrainingDataConfig(args.config_path);
  if (threads_given) options.threads = args.threads;
  options.threads = std::min<int>(options.threads, std::max(1u, std::thread::hardware_concurrency()));
  CheckMayReplace({"--out", args.run.output_path}, args.run.overwrite, OwnedTrainingData());
  std::printf("features training-data: %d scene(s), %d clock time(s) x %d frame(s) each, %d thread(s)\n",
              options.scenes.scenes, options.scenes.hours_per_scene, options.scenes.frames_per_hour,
              options.threads);
  std::fflush(stdout);
  const TrainingDataSummary summary =
      GenerateTrainingData(options, args.run, [](const TrainingSceneProgress& p) {
        std::printf("scene %d/%d (%s): %d frames, %d image pairs, %lld pairs, %.1f s\n", p.index + 1, p.scenes,
                    p.split.c_str(), p.frames, p.image_pairs, static_cast<long long>(p.pairs), p.wall_s);
        std::fflush(stdout);
      });
  const TrainingDataManifest& m = summary.manifest;
  std::printf("wrote %lld pairs (train %lld, validation %lld; %lld + %lld bytes) to %s in %.1f s\n",
              static_cast<long long>(m.pairs), static_cast<long long>(m.train_pairs),
              static_cast<long long>(m.validation_pairs), static_cast<long long>(m.files[0].bytes),
              static_cast<long long>(m.files[1].bytes), summary.output_path.c_str(), summary.wall_s);
  return 0;
}

}  // namespace

std::pair<CLI::App*, RunFn> AddTrainingDataCommand(CLI::App& features) {
  auto args = std::make_shared<TrainingDataArgs>();
  CLI::App* command = features.add_subcommand(
      "training-data", "Render the learned descriptor's training pairs (patches of one surface point at two hours)");
  command->add_option("--config", args->config_path, "training config (JSON: its \"data\" section)")->required();
  command->add_option("--out", args->run.output_path, "training-data folder to create")->required();
  command->add_flag("--overwrite", args->run.overwrite, "replace training data duskmap wrote");
  CLI::Option* threads = command->add_option("--threads", args->threads, "scenes rendered in parallel (overrides the config)");
  return {command, [args, threads] { return RunTrainingData(*args, threads->count() > 0); }};
}

}  // namespace duskmap::cli
