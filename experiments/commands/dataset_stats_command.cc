// `duskmap dataset-stats`: the realism matrix of a multi-session dataset
// (median SIFT and ORB inlier ratios at corresponding ground-truth poses).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>

#include "experiments/command_registry.h"
#include "slam/core/check.h"
#include "slam/eval/realism.h"
#include "slam/io/synthetic_dataset.h"
#include "slam/io/tum_dataset.h"

namespace duskmap::cli {
namespace {

struct StatsArgs {
  std::string dataset_path;
  std::string pairs_csv;
  RealismOptions options;
};

// One row per corresponding frame pair, for finding the poses where sessions fail to match.
std::string PairsCsv(const RealismReport& r) {
  std::ostringstream out;
  out << "session_a,session_b,anchor,frame_a,frame_b,sift_keypoints_a,sift_keypoints_b,"
         "sift_matches,sift_correct,orb_matches,orb_correct\n";
  for (const RealismPair& p : r.pairs) {
    out << r.sessions[p.session_a] << ',' << r.sessions[p.session_b] << ',' << p.anchor << ',' << p.frame_a << ','
        << p.frame_b << ',' << p.sift_keypoints_a << ',' << p.sift_keypoints_b << ',' << p.sift_matches << ','
        << p.sift_correct << ',' << p.orb_matches << ',' << p.orb_correct << '\n';
  }
  return out.str();
}

void PrintMatrix(const char* title, const RealismReport& r, const Eigen::MatrixXd& m) {
  std::printf("\n%s\n%-6s", title, "");
  for (const std::string& s : r.sessions) std::printf(" %5s", s.c_str());
  std::printf("\n");
  for (size_t a = 0; a < r.sessions.size(); ++a) {
    std::printf("%-2s%-5s", r.sessions[a].c_str(), r.clock_times[a].c_str());
    for (size_t b = 0; b < r.sessions.size(); ++b) {
      if (std::isnan(m(a, b))) std::printf("     -");
      else std::printf(" %5.2f", m(a, b));
    }
    std::printf("\n");
  }
}

RunFn SetupStats(CLI::App& command) {
  auto args = std::make_shared<StatsArgs>();
  command.add_option("--dataset", args->dataset_path, "synthetic dataset folder (manifest.json)")->required();
  command.add_option("--frame-step", args->options.frame_step, "anchor spacing in frames")->capture_default_str();
  command.add_option("--max-features", args->options.max_features, "features per frame and detector")
      ->capture_default_str();
  command.add_option("--sift-contrast", args->options.sift_contrast_threshold,
                     "SIFT contrast threshold (OpenCV's default; the paper's experiments use 0.02)")
      ->capture_default_str();
  command.add_option("--max-error-px", args->options.max_reprojection_px,
                     "a match is correct when ground truth reprojects its keypoint within this many pixels")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  command.add_option("--min-correct", args->options.min_correct_matches,
                     "correct matches a frame pair needs to count as found")
      ->capture_default_str();
  command.add_option("--pairs-csv", args->pairs_csv,
                     "also write every corresponding frame pair's keypoints, matches and correct matches here");
  return [args] {
    // The options before anything is read: each message names its flag.
    try {
      args->options.Check();
    } catch (const ConfigError& e) {
      throw ConfigError(std::string("dataset-stats: ") + e.what());
    }
    // A path that cannot be written fails before the minutes of matching; an
    // existing file is left as it is until the new one is complete.
    if (!args->pairs_csv.empty()) {
      const bool existed = std::filesystem::exists(args->pairs_csv);
      SLAM_THROW_IF_NOT(InputError, std::ofstream(args->pairs_csv, std::ios::app).good())
          << args->pairs_csv << ": cannot write";
      if (!existed) std::filesystem::remove(args->pairs_csv);
    }
    const bool synthetic = std::filesystem::exists(args->dataset_path + "/" + kManifestFileName);
    std::unique_ptr<DatasetReader> dataset =
        synthetic ? OpenSyntheticDataset(args->dataset_path) : OpenTumDataset(args->dataset_path);
    const RealismReport r = ComputeRealism(*dataset, args->options);
    std::printf("realism of %s: %d anchors (every %d frames of session %s), %d features, SIFT contrast %.3f, "
                "ratio %.2f, inlier = ground-truth reprojection within %.1f px\n",
                args->dataset_path.c_str(), r.anchors, args->options.frame_step, r.sessions[0].c_str(),
                args->options.max_features, args->options.sift_contrast_threshold, args->options.ratio_test,
                args->options.max_reprojection_px);
    PrintMatrix("SIFT median inlier ratio", r, r.sift_inlier_ratio);
    PrintMatrix("ORB median inlier ratio", r, r.orb_inlier_ratio);
    PrintMatrix("SIFT median correct matches", r, r.sift_median_inliers);
    char title[96];
    std::snprintf(title, sizeof(title), "SIFT fraction of frame pairs with >= %d correct matches",
                  args->options.min_correct_matches);
    PrintMatrix(title, r, r.sift_found_fraction);
    std::printf("\ncomputed in %.1f s\n", r.wall_s);
    if (!args->pairs_csv.empty()) {
      std::ofstream pairs_out(args->pairs_csv);
      pairs_out << PairsCsv(r);
      pairs_out.flush();
      SLAM_THROW_IF_NOT(InputError, pairs_out.good()) << args->pairs_csv << ": cannot write";
      std::printf("frame pairs written to %s\n", args->pairs_csv.c_str());
    }
    return 0;
  };
}

const bool kRegistered = RegisterCommand(
    {"dataset-stats", "Realism of a multi-session dataset: SIFT/ORB inlier-ratio matrices", &SetupStats});

}  // namespace
}  // namespace duskmap::cli
