// `duskmap features eval`: the real-image illumination benchmark of the
// feature types on Oxford/HPatches-layout sequences, or on WxBS-layout pairs
// scored by epipolar geometry (JSON + Markdown).
// `duskmap features export`: a dataset's features in hloc's HDF5 layout, and
// the list of its images for an external extractor (docs/features.md).
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>

#include <opencv2/core/utility.hpp>

#include "experiments/command_registry.h"
#include "slam/core/check.h"
#include "slam/core/json_fields.h"
#include "slam/datasets/dataset_factory.h"
#include "slam/engine/feature_export.h"
#include "slam/features/epipolar_eval.h"
#include "slam/features/feature_options_json.h"
#include "slam/features/sequence_eval.h"
#include "slam/io/output_safety.h"

namespace duskmap::cli {
namespace {

struct EvalArgs {
  std::string data;
  std::string types = "surf,sift,brief,brisk,kaze,daisy,orb,akaze,freak";
  std::string config;
  std::string out_dir;
  std::string layout = "auto";
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
  SLAM_THROW_IF_NOT(ConfigError, args.layout == "auto" || args.layout == "homography" || args.layout == "pairs")
      << "features eval: --layout must be auto, homography or pairs, got '" << args.layout << "'";
  cv::setNumThreads(args.threads);  // timings per core by default, like the benchmark
  FeatureOptions features;
  if (!args.config.empty()) {
    JsonFields fields(ReadJsonFile(args.config), args.config);
    features = ReadJsonOptions<FeatureOptions>(fields);
  }
  std::string table;
  nlohmann::json json;
  const std::vector<CorrespondencePair> pairs =
      args.layout == "homography" ? std::vector<CorrespondencePair>() : FindCorrespondencePairs(args.data);
  SLAM_THROW_IF_NOT(InputError, args.layout != "pairs" || !pairs.empty())
      << args.data << ": no pair folder (01.*, 02.*, corrs.txt) here or one or two levels down";
  if (!pairs.empty()) {
    EpipolarEvalOptions options;
    options.types = SplitComma(args.types);
    options.features = features;
    std::cout << "features eval: " << pairs.size() << " pair(s) with hand-clicked correspondences in "
              << args.data << ", " << options.types.size() << " type(s)\n";
    const EpipolarEvalResult result = EvaluateOnCorrespondencePairs(pairs, options);
    table = ToMarkdown(result);
    json = ToJson(result);
  } else {
    FeatureEvalOptions options;
    options.types = SplitComma(args.types);
    options.features = features;
    const auto sequences = FindHomographySequences(args.data);
    std::cout << "features eval: " << sequences.size() << " sequence(s) in " << args.data << ", "
              << options.types.size() << " type(s)\n";
    const FeatureEvalResult result = EvaluateFeatures(sequences, options);
    table = ToMarkdown(result);
    json = ToJson(result);
  }
  std::cout << table;
  if (!args.out_dir.empty()) {
    std::filesystem::create_directories(args.out_dir);
    const std::filesystem::path dir(args.out_dir);
    WriteFile(dir / "features_eval.json", json.dump(2) + "\n");
    WriteFile(dir / "features_eval.md", "Sequences: " + args.data + "\n\n" + table);
    std::cout << "wrote " << (dir / "features_eval.json").string() << " and "
              << (dir / "features_eval.md").string() << "\n";
  }
  return 0;
}

struct ExportArgs {
  std::string dataset;
  std::string format = "auto";
  std::vector<std::string> sessions;
  std::string type;
  std::string config;
  std::string output;
  std::string image_list;
  bool overwrite = false;
};

int RunExport(const ExportArgs& args, bool type_given) {
  CheckOutputsApartFromInputs({{"--output", args.output}, {"--image-list", args.image_list}},
                              {{"--dataset", args.dataset}, {"--config", args.config}});
  const OwnedOutput export_file{"a duskmap feature export", [](const std::filesystem::path& p) {
                                  return IsDuskmapFeatureExport(p.string());
                                }};
  const OwnedOutput image_list{"a file (image lists are plain text)",
                               [](const std::filesystem::path& p) {
                                 return std::filesystem::is_regular_file(p);
                               }};
  if (!args.output.empty()) CheckMayReplace({"--output", args.output}, args.overwrite, export_file);
  if (!args.image_list.empty()) {
    CheckMayReplace({"--image-list", args.image_list}, args.overwrite, image_list);
  }
  FeatureOptions features;
  if (!args.config.empty()) {
    JsonFields fields(ReadJsonFile(args.config), args.config);
    features = ReadJsonOptions<FeatureOptions>(fields);
  }
  SLAM_THROW_IF_NOT(ConfigError, args.output.empty() || type_given || !args.config.empty())
      << "features export: --output needs --type (or a --config naming one)";
  if (type_given) features.type = args.type;
  features.Check();
  FeatureExportOptions options;
  options.sessions = args.sessions;
  options.output_path = args.output;
  options.image_list_path = args.image_list;
  options.Check();
  const auto dataset = OpenDataset(args.dataset, args.format);
  const FeatureExportSummary summary =
      ExportFeatures(*dataset, features, options, [](const std::string& session, int64_t frames) {
        std::cout << "features export: session " << session << ": " << frames << " frames\n";
      });
  std::cout << "features export: " << summary.sessions << " session(s), " << summary.frames
            << " frames";
  if (!args.output.empty()) {
    std::cout << ", " << features.type << " " << summary.mean_features << " features and "
              << summary.mean_extract_ms << " ms per frame; wrote " << args.output << " ("
              << summary.output_bytes << " bytes)";
  }
  if (!args.image_list.empty()) std::cout << "; image list " << args.image_list;
  std::cout << "\n";
  return 0;
}

RunFn SetupFeatures(CLI::App& command) {
  command.require_subcommand(1);
  auto args = std::make_shared<EvalArgs>();
  CLI::App* eval = command.add_subcommand(
      "eval", "Per feature type: repeatability, matching score, MMA and homography accuracy on sequences, or pairs solved by epipolar geometry on WxBS-style pairs");
  eval->add_option("--data", args->data,
                   "sequence folder (img1 + imgN + H1toNp), pair folder (01.*, 02.*, corrs.txt: "
                   "WxBS), or a folder of either (pairs also in category folders)")
      ->required();
  eval->add_option("--layout", args->layout,
                   "auto (pairs when any pair folder is found), homography, pairs");
  eval->add_option("--types", args->types, "comma-separated feature types");
  eval->add_option("--config", args->config, "JSON feature options (FeatureOptions)");
  eval->add_option("--threads", args->threads, "OpenCV threads (1: per-core timings)");
  eval->add_option("--out", args->out_dir, "folder for features_eval.json and features_eval.md");
  auto export_args = std::make_shared<ExportArgs>();
  CLI::App* exporter = command.add_subcommand(
      "export", "Write a dataset's features in hloc's HDF5 layout, or list its images for an external extractor");
  exporter->add_option("--dataset", export_args->dataset, "dataset folder")->required();
  exporter->add_option("--dataset-format,--format", export_args->format,
                       "dataset format: auto (default), synthetic, tum, rtabmap-images");
  exporter->add_option("--sessions", export_args->sessions, "sessions to export (default: all)")
      ->delimiter(',');
  exporter->add_option("--type", export_args->type, "feature type (surf, sift, brief, ..., h5)");
  exporter->add_option("--config", export_args->config, "JSON feature options (FeatureOptions)");
  exporter->add_option("--output", export_args->output,
                       "the .h5 to write: one group per image, \"<session>/<image name>\"");
  exporter->add_option("--image-list", export_args->image_list,
                       "write \"<group name>\\t<image file>\" per frame, for an external extractor");
  exporter->add_flag("--overwrite", export_args->overwrite,
                     "replace an existing export (only a duskmap export) or image list");
  CLI::Option* type_option = exporter->get_option("--type");
  return [args, eval, export_args, exporter, type_option] {
    if (exporter->parsed()) return RunExport(*export_args, type_option->count() > 0);
    SLAM_THROW_IF_NOT(ConfigError, eval->parsed()) << "features: expected a subcommand (eval, export)";
    return RunEval(*args);
  };
}

const bool kRegistered = RegisterCommand(
    {"features", "Evaluate feature extractors on real image sequences; export features in hloc's HDF5 layout", &SetupFeatures});

}  // namespace
}  // namespace duskmap::cli
