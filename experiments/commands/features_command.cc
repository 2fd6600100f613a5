// `duskmap features eval`: the real-image illumination benchmark of the
// feature types on Oxford/HPatches-layout sequences, or on WxBS-layout pairs
// scored by epipolar geometry (JSON + Markdown).
// `duskmap features export`: a dataset's features in hloc's HDF5 layout, and
// the list of its images for an external extractor (docs/features.md).
// `duskmap features training-data`: training_data_command.cc.
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>

#include <opencv2/core/utility.hpp>

#include "experiments/command_registry.h"
#include "experiments/commands/training_data_command.h"
#include "slam/core/check.h"
#include "slam/core/json_fields.h"
#include "slam/datasets/dataset_factory.h"
#include "slam/engine/feature_export.h"
#include "slam/features/eval/epipolar_eval.h"
#include "slam/features/eval/eval_pairs.h"
#include "slam/features/eval/image_sequence.h"
#include "slam/features/eval/sequence_eval.h"
#include "slam/features/feature_options.h"
#include "slam/features/feature_options_json.h"
#include "slam/io/output_safety.h"
#include "slam/io/path_status.h"

namespace duskmap::cli {
namespace {

std::string Joined(const std::vector<std::string>& names, const char* separator) {
  std::string text;
  for (const std::string& name : names) text += (text.empty() ? "" : separator) + name;
  return text;
}

struct EvalArgs {
  std::string data;
  std::string types = Joined(BuiltInFeatureTypeNames(), ",");
  std::string config;
  std::string out_dir;
  std::string layout = "auto";
  std::string pairs;
  std::string pairs_file;
  int threads = 1;
};

// "--types surf,SIFT": each name as FeatureTypeNames() spells it.
std::vector<std::string> ParseTypes(const std::string& text) {
  std::vector<std::string> types;
  std::stringstream in(text);
  for (std::string part; std::getline(in, part, ',');) {
    if (!part.empty()) types.push_back(FeatureTypeFromName(part, "features eval: --types"));
  }
  SLAM_THROW_IF_NOT(ConfigError, !types.empty()) << "features eval: --types names no feature type";
  return types;
}

// Written whole or not at all, through the one publish helper (replaced each
// run, as documented), with the system's reason when the disk is full.
void WriteFile(const std::filesystem::path& path, const std::string& text) {
  WriteFileAtomically(path.string(), [&text](std::ostream& out) { out << text; });
}

// --out is a folder: refused before any work when something else is there,
// or when the nearest part of its path that exists is not a folder.
void CheckOutFolder(const std::string& out_dir) {
  const std::filesystem::file_status status = PathStatus(out_dir);
  SLAM_THROW_IF_NOT(ConfigError, status.type() == std::filesystem::file_type::not_found ||
                                     status.type() == std::filesystem::file_type::directory)
      << "features eval: --out " << out_dir
      << ": exists and is not a folder (features_eval.json and features_eval.md are written into a folder)";
  std::filesystem::path existing = std::filesystem::path(out_dir).parent_path();
  while (!existing.empty() && !PathExists(existing)) existing = existing.parent_path();
  SLAM_THROW_IF_NOT(ConfigError, existing.empty() || IsDirectoryPath(existing))
      << "features eval: --out " << out_dir << ": " << existing.string() << " is not a folder";
}

void CreateOutFolder(const std::string& out_dir) {
  std::error_code error;
  std::filesystem::create_directories(out_dir, error);
  SLAM_THROW_IF_NOT(InputError, !error) << out_dir << ": cannot create the folder: " << error.message();
}

std::vector<PairSelector> PairSelectors(const EvalArgs& args) {
  if (!args.pairs_file.empty()) return ReadPairListFile(args.pairs_file);
  if (!args.pairs.empty()) return ParsePairList(args.pairs);
  return {};
}

// What `features eval` prints and writes: the report's header, its table
// (Markdown) and its JSON.
struct EvalOutput {
  std::string header;
  std::string table;
  nlohmann::json json;
};

EvalOutput EvalPairs(const EvalArgs& args, std::vector<CorrespondencePair> pairs,
                     const std::vector<PairSelector>& selectors,
                     const std::vector<std::string>& types, const FeatureOptions& features) {
  if (!selectors.empty()) pairs = SelectCorrespondencePairs(pairs, selectors);
  EpipolarEvalOptions options;
  options.types = types;
  options.features = features;
  std::cout << "features eval: " << pairs.size() << " pair(s) with hand-clicked correspondences in "
            << args.data << ", " << options.types.size() << " type(s)\n";
  const EpipolarEvalResult result = EvaluateOnCorrespondencePairs(pairs, options);
  return {"Pairs: " + args.data + "\n\n", ToMarkdown(result), ToJson(result)};
}

EvalOutput EvalSequences(const EvalArgs& args, const std::vector<PairSelector>& selectors,
                         const std::vector<std::string>& types, const FeatureOptions& features) {
  std::optional<SequenceLayout> layout;
  if (args.layout == "homography") layout = SequenceLayout::kHomography;
  if (args.layout == "static") layout = SequenceLayout::kStatic;
  SequenceSet set = FindImageSequences(args.data, layout);
  std::string how = set.detected ? (set.layout == SequenceLayout::kStatic ? "detected: no H1toNp file"
                                                                          : "detected: H1toNp files")
                                 : "--layout " + args.layout;
  if (set.layout == SequenceLayout::kStatic) {
    for (const ImageSequence& seq : set.sequences) {
      if (HasHomographyFiles(seq.directory)) how += "; the H files of " + seq.name + " are not used";
    }
  }
  if (!selectors.empty()) SelectSequencePairs(selectors, &set.sequences);
  FeatureEvalOptions options;
  options.types = types;
  options.features = features;
  size_t pair_count = 0;
  for (const ImageSequence& seq : set.sequences) pair_count += seq.pairs.size();
  const std::string layout_line =
      std::string("layout ") + SequenceLayoutName(set.layout) + " (" + how + ")";
  std::cout << "features eval: " << set.sequences.size() << " sequence(s) in " << args.data << ", "
            << layout_line << ", " << pair_count << " pair(s), " << options.types.size() << " type(s)\n";
  const FeatureEvalResult result = EvaluateFeatures(set.sequences, options);
  return {"Sequences: " + args.data + "\n\nLayout: " + std::string(SequenceLayoutName(set.layout)) +
              " (" + how + ")\n\n",
          ToMarkdown(result), ToJson(result)};
}

int RunEval(const EvalArgs& args) {
  SLAM_THROW_IF_NOT(ConfigError, args.threads >= 1) << "features eval: --threads must be >= 1";
  SLAM_THROW_IF_NOT(ConfigError, args.layout == "auto" || args.layout == "homography" ||
                                     args.layout == "static" || args.layout == "pairs")
      << "features eval: --layout must be auto, homography, static or pairs, got '" << args.layout << "'";
  const std::vector<std::string> types = ParseTypes(args.types);
  const std::vector<PairSelector> selectors = PairSelectors(args);
  if (!args.out_dir.empty()) CheckOutFolder(args.out_dir);
  cv::setNumThreads(args.threads);  // timings per core by default, like the benchmark
  FeatureOptions features;
  if (!args.config.empty()) {
    JsonFields fields(ReadJsonFile(args.config), args.config);
    features = ReadJsonOptions<FeatureOptions>(fields);
  }
  const bool sequence_layout = args.layout == "homography" || args.layout == "static";
  std::vector<CorrespondencePair> pairs =
      sequence_layout ? std::vector<CorrespondencePair>() : FindCorrespondencePairs(args.data);
  SLAM_THROW_IF_NOT(InputError, args.layout != "pairs" || !pairs.empty())
      << args.data << ": no pair folder (01.*, 02.*, corrs.txt) here or one or two levels down";
  const EvalOutput output = pairs.empty()
                                ? EvalSequences(args, selectors, types, features)
                                : EvalPairs(args, std::move(pairs), selectors, types, features);
  std::cout << output.table;
  if (!args.out_dir.empty()) {
    CreateOutFolder(args.out_dir);
    const std::filesystem::path dir(args.out_dir);
    WriteFile(dir / "features_eval.json", output.json.dump(2) + "\n");
    WriteFile(dir / "features_eval.md", output.header + output.table);
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
  if (type_given) features.type = FeatureTypeFromName(args.type, "features export: --type");
  features.Check();
  FeatureExportOptions options;
  options.sessions = args.sessions;
  options.output_path = args.output;
  options.image_list_path = args.image_list;
  options.overwrite = args.overwrite;
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
                   "sequence folder (img1 + imgN + H1toNp, or a fixed camera's images), pair folder (01.*, 02.*, corrs.txt: "
                   "WxBS), or a folder of either (pairs also in category folders)")
      ->required();
  eval->add_option("--layout", args->layout,
                   "auto (default: pairs when a pair folder is found, else homography when the sequences have "
                   "H1toNp files, static when none), homography, static (a fixed camera: identity ground "
                   "truth, no H files), pairs");
  eval->add_option("--types", args->types,
                   "comma-separated feature types, any case: " + Joined(FeatureTypeNames(), ", ") +
                       " (superpoint, onnx and h5 need --config); default: " + args->types);
  CLI::Option* pairs_option = eval->add_option(
      "--pairs", args->pairs,
      "score only these pairs: image indices <i>-<j> (1-5,1-6), <sequence>/<i>-<j> for one sequence, or "
      "pair names (WGALBS/kremlin) in the pairs layout; default: the first image (img1) with every other");
  eval->add_option("--pairs-file", args->pairs_file,
                   "the same as --pairs, from a file: comma- or line-separated, '#' starts a comment")
      ->excludes(pairs_option);
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
  exporter->add_option("--type", export_args->type,
                       "feature type, any case: " + Joined(FeatureTypeNames(), ", "));
  exporter->add_option("--config", export_args->config, "JSON feature options (FeatureOptions)");
  exporter->add_option("--output", export_args->output,
                       "the .h5 to write: one group per image, \"<session>/<image name>\"");
  exporter->add_option("--image-list", export_args->image_list,
                       "write \"<group name>\\t<image file>\" per frame, for an external extractor");
  exporter->add_flag("--overwrite", export_args->overwrite,
                     "replace an existing export (only a duskmap export) or image list");
  CLI::Option* type_option = exporter->get_option("--type");
  const auto [training, run_training] = AddTrainingDataCommand(command);
  return [args, eval, export_args, exporter, type_option, training = training, run_training = run_training] {
    if (exporter->parsed()) return RunExport(*export_args, type_option->count() > 0);
    if (training->parsed()) return run_training();
    SLAM_THROW_IF_NOT(ConfigError, eval->parsed()) << "features: expected a subcommand (eval, export, training-data)";
    return RunEval(*args);
  };
}

const bool kRegistered = RegisterCommand(
    {"features", "Evaluate feature extractors on real image sequences; export features in hloc's HDF5 layout; render training pairs", &SetupFeatures});

}  // namespace
}  // namespace duskmap::cli
