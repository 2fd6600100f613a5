// `duskmap features eval`: the real-image illumination benchmark of the
// feature types on Oxford/HPatches-layout sequences (JSON + Markdown).
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>

#include <opencv2/core/utility.hpp>

#include "experiments/command_registry.h"
#include "slam/core/check.h"
#include "slam/core/json_fields.h"
#include "slam/features/sequence_eval.h"

namespace duskmap::cli {
namespace {

struct EvalArgs {
  std::string data;
  std::string types = "surf,sift,brief,brisk,kaze,daisy,orb,akaze,freak";
  std::string config;
  std::string out_dir;
  int threads = 1;
};

std::vector<std::string> SplitComma(const std::string& text) {
  std::vector<std::string> parts;
  std::stringstream in(text);
  for (std::string part; std::getline(in, part, ',');) {
    if (!part.empty()) parts.push_back(part);
  }
  return parts;
}

void WriteFile(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path);
  SLAM_THROW_IF_NOT(InputError, out.good()) << path.string() << ": cannot write";
  out << text;
}

int RunEval(const EvalArgs& args) {
  SLAM_THROW_IF_NOT(ConfigError, args.threads >= 1) << "features eval: --threads must be >= 1";
  cv::setNumThreads(args.threads);  // timings per core by default, like the benchmark
  FeatureEvalOptions options;
  options.types = SplitComma(args.types);
  if (!args.config.empty()) {
    JsonFields fields(ReadJsonFile(args.config), args.config);
    options.features = ReadFeatureOptions(fields);
  }
  const auto sequences = FindHomographySequences(args.data);
  std::cout << "features eval: " << sequences.size() << " sequence(s) in " << args.data << ", "
            << options.types.size() << " type(s)\n";
  const FeatureEvalResult result = EvaluateFeatures(sequences, options);
  const std::string table = ToMarkdown(result);
  std::cout << table;
  if (!args.out_dir.empty()) {
    std::filesystem::create_directories(args.out_dir);
    const std::filesystem::path dir(args.out_dir);
    WriteFile(dir / "features_eval.json", ToJson(result).dump(2) + "\n");
    WriteFile(dir / "features_eval.md", "Sequences: " + args.data + "\n\n" + table);
    std::cout << "wrote " << (dir / "features_eval.json").string() << " and "
              << (dir / "features_eval.md").string() << "\n";
  }
  return 0;
}

RunFn SetupFeatures(CLI::App& command) {
  command.require_subcommand(1);
  auto args = std::make_shared<EvalArgs>();
  CLI::App* eval = command.add_subcommand(
      "eval", "Repeatability, matching score, MMA and homography accuracy per feature type");
  eval->add_option("--data", args->data,
                   "sequence folder (img1 + imgN + H1toNp) or a folder of such folders")
      ->required();
  eval->add_option("--types", args->types, "comma-separated feature types");
  eval->add_option("--config", args->config, "JSON feature options (FeatureOptions)");
  eval->add_option("--threads", args->threads, "OpenCV threads (1: per-core timings)");
  eval->add_option("--out", args->out_dir, "folder for features_eval.json and features_eval.md");
  return [args, eval] {
    SLAM_THROW_IF_NOT(ConfigError, eval->parsed()) << "features: expected a subcommand (eval)";
    return RunEval(*args);
  };
}

const bool kRegistered = RegisterCommand(
    {"features", "Evaluate feature extractors on real image sequences", &SetupFeatures});

}  // namespace
}  // namespace duskmap::cli
