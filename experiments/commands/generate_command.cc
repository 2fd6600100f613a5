// `duskmap generate`: writes the synthetic sunset-apartment dataset.
#include <cstdio>
#include <iostream>
#include <memory>

#include <algorithm>
#include <thread>

#include "experiments/command_registry.h"
#include "slam/core/check.h"
#include "slam/io/output_safety.h"
#include "slam/synthetic/generator.h"
#include "slam/synthetic/generator_config.h"

namespace duskmap::cli {
namespace {

struct GenerateArgs {
  std::string config_path;
  std::string textures_dir;
  int threads = 0;  // used when --threads is given
  GenerateOptions options;
};

RunFn SetupGenerate(CLI::App& command) {
  auto args = std::make_shared<GenerateArgs>();
  command.add_option("--config", args->config_path, "generator config (JSON)")->required();
  command.add_option("--output", args->options.output_path, "dataset folder to create")->required();
  command.add_flag("--overwrite", args->options.overwrite, "replace an existing dataset folder (only one duskmap generated)");
  command.add_flag("--preview", args->options.preview, "also write previews/ (PNG)");
  command.add_option("--textures", args->textures_dir, "folder of images for pictures and posters");
  CLI::Option* threads = command.add_option("--threads", args->threads,
                                            "sessions generated in parallel (overrides the config)");
  return [args, threads] {
    const bool threads_given = threads->count() > 0;
    SLAM_THROW_IF_NOT(ConfigError, !threads_given || args->threads >= 1)
        << "--threads: must be >= 1, got " << args->threads;
    GeneratorConfig config = ReadGeneratorConfig(args->config_path);
    if (!args->textures_dir.empty()) config.scene.textures_dir = args->textures_dir;
    if (threads_given) config.threads = args->threads;
    // More threads than cores only adds memory (one frame buffer set each).
    config.threads = std::min<int>(config.threads,
                                   std::max(1u, std::thread::hardware_concurrency()));
    // The dataset folder is replaced as a whole: none of the inputs may be in it.
    CheckOutputsApartFromInputs({{"--output", args->options.output_path}},
                                {{"--config", args->config_path}, {"--textures", args->textures_dir}});
    for (const NamedPath& input : {NamedPath{"--config", args->config_path},
                                   NamedPath{"--textures", args->textures_dir}}) {
      SLAM_THROW_IF_NOT(InputError, input.path.empty() ||
                                        !IsSameOrInside(input.path, args->options.output_path))
          << args->options.output_path << ": --output would replace the folder holding "
          << input.flag << " " << input.path << "; choose another output";
    }
    const GenerateSummary summary = GenerateDataset(config, args->options);
    std::printf("%-4s %-6s %6s %8s %8s %8s %8s %9s %7s\n", "sess", "clock", "frames", "dist_m", "sun_deg",
                "bright", "gain", "odo_err_m", "wall_s");
    for (const GeneratedSessionSummary& s : summary.sessions) {
      std::printf("%-4s %-6s %6d %8.1f %8.1f %8.3f %8.2f %9.3f %7.1f\n", s.name.c_str(), s.clock_time.c_str(),
                  s.frames, s.distance_m, s.sun_elevation_deg, s.mean_brightness, s.mean_gain,
                  s.odometry_final_error_m, s.wall_s);
    }
    std::printf("wrote %zu sessions to %s in %.1f s (%d threads)\n", summary.sessions.size(),
                summary.output_path.c_str(), summary.wall_s, config.threads);
    return 0;
  };
}

const bool kRegistered = RegisterCommand(
    {"generate", "Generate the synthetic sunset-apartment RGB-D dataset", &SetupGenerate});

}  // namespace
}  // namespace duskmap::cli
