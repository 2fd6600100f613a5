#include "slam/features/sequence_eval.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>

#include <opencv2/imgcodecs.hpp>

#include "slam/core/check.h"
#include "slam/features/eval_image.h"
#include "slam/core/timer.h"
#include "slam/features/feature_extractor.h"

namespace duskmap {
namespace fs = std::filesystem;
namespace {

std::string FindImage(const fs::path& dir, int index) {
  for (const char* ext : {".ppm", ".png", ".jpg", ".pgm"}) {
    const fs::path p = dir / ("img" + std::to_string(index) + ext);
    if (fs::exists(p)) return p.string();
  }
  return "";
}

cv::Matx33d ReadHomography(const fs::path& path) {
  std::ifstream in(path);
  SLAM_THROW_IF_NOT(InputError, in.good()) << path.string() << ": cannot open homography";
  cv::Matx33d h;
  for (int i = 0; i < 9; ++i) {
    SLAM_THROW_IF_NOT(InputError, static_cast<bool>(in >> h.val[i]))
        << path.string() << ": expected 9 numbers";
  }
  SLAM_THROW_IF_NOT(InputError, std::abs(cv::determinant(h)) > 1e-12)
      << path.string() << ": singular homography";
  return h;
}

double Mean(double sum, int n) { return n == 0 ? 0.0 : sum / n; }

TypeSummary EvaluateType(const std::vector<HomographySequence>& sequences,
                         const FeatureEvalOptions& options, const std::string& type) {
  FeatureOptions feature_options = options.features;
  feature_options.type = type;
  const auto extractor = CreateFeatureExtractor(feature_options);
  TypeSummary s;
  s.type = type;
  double keypoints = 0.0, time_ms = 0.0, homographies = 0.0;
  int images = 0;
  auto extract = [&](const cv::Mat& image) {
    Stopwatch watch;
    FrameFeatures f = extractor->Extract(image);
    time_ms += watch.ElapsedMs();
    keypoints += static_cast<double>(f.size());
    ++images;
    if (!f.empty()) s.descriptor_bytes = static_cast<int>(f.DescriptorBytes());
    return f;
  };
  for (const HomographySequence& seq : sequences) {
    const cv::Mat reference = ReadEvalImage(seq.reference_path);
    const FrameFeatures reference_features = extract(reference);
    for (size_t t = 0; t < seq.target_paths.size(); ++t) {
      const cv::Mat target = ReadEvalImage(seq.target_paths[t]);
      PairRecord record;
      record.sequence = seq.name;
      record.target_index = static_cast<int>(t) + 2;
      record.metrics = EvaluatePair(reference_features, reference.size(), extract(target),
                                    target.size(), seq.target_from_reference[t], options.metrics);
      const PairMetrics& m = record.metrics;
      s.repeatability += m.repeatability;
      s.matching_score += m.matching_score;
      for (size_t k = 0; k < 3; ++k) s.mma[k] += m.mma[k];
      homographies += m.homography_correct;
      s.records.push_back(record);
    }
  }
  s.pairs = static_cast<int>(s.records.size());
  s.repeatability = Mean(s.repeatability, s.pairs);
  s.matching_score = Mean(s.matching_score, s.pairs);
  for (double& v : s.mma) v = Mean(v, s.pairs);
  s.homography_accuracy = Mean(homographies, s.pairs);
  s.keypoints_per_image = Mean(keypoints, images);
  s.extraction_ms = Mean(time_ms, images);
  return s;
}

}  // namespace

HomographySequence ReadHomographySequence(const std::string& directory) {
  const fs::path dir(directory);
  HomographySequence seq;
  seq.name = dir.filename().empty() ? dir.parent_path().filename().string() : dir.filename().string();
  seq.reference_path = FindImage(dir, 1);
  SLAM_THROW_IF_NOT(InputError, !seq.reference_path.empty())
      << directory << ": no reference image img1.{ppm,png,jpg,pgm}";
  for (int n = 2; n < 100; ++n) {
    const std::string image = FindImage(dir, n);
    const fs::path h = dir / ("H1to" + std::to_string(n) + "p");
    if (image.empty() || !fs::exists(h)) break;
    seq.target_paths.push_back(image);
    seq.target_from_reference.push_back(ReadHomography(h));
  }
  SLAM_THROW_IF_NOT(InputError, !seq.target_paths.empty())
      << directory << ": no target image with a homography (img2 + H1to2p)";
  return seq;
}

std::vector<HomographySequence> FindHomographySequences(const std::string& root) {
  SLAM_THROW_IF_NOT(InputError, fs::is_directory(root)) << root << ": not a directory";
  if (!FindImage(root, 1).empty()) return {ReadHomographySequence(root)};
  std::vector<std::string> dirs;
  for (const auto& entry : fs::directory_iterator(root)) {
    if (entry.is_directory() && !FindImage(entry.path(), 1).empty()) {
      dirs.push_back(entry.path().string());
    }
  }
  std::sort(dirs.begin(), dirs.end());
  SLAM_THROW_IF_NOT(InputError, !dirs.empty())
      << root << ": no sequence (folder with img1 and H1to2p) found";
  std::vector<HomographySequence> sequences;
  for (const std::string& d : dirs) sequences.push_back(ReadHomographySequence(d));
  return sequences;
}

void FeatureEvalOptions::Check() const {
  SLAM_THROW_IF_NOT(ConfigError, !types.empty()) << "features eval: no feature type given";
  for (const std::string& t : types) {
    FeatureOptions o = features;
    o.type = t;
    o.Check();
  }
  metrics.Check();
}

FeatureEvalResult EvaluateFeatures(const std::vector<HomographySequence>& sequences,
                                   const FeatureEvalOptions& options) {
  options.Check();
  FeatureEvalResult result;
  result.options = options;
  for (const auto& seq : sequences) result.sequences.push_back(seq.name);
  for (const std::string& type : options.types) {
    result.types.push_back(EvaluateType(sequences, options, type));
  }
  return result;
}

nlohmann::json ToJson(const FeatureEvalResult& result) {
  nlohmann::json j;
  j["sequences"] = result.sequences;
  j["thresholds_px"] = {{"repeatability", result.options.metrics.repeatability_px},
                        {"correct_match", result.options.metrics.correct_match_px},
                        {"mma", result.options.metrics.mma_px},
                        {"homography_corner_error", result.options.metrics.corner_error_px}};
  j["max_features"] = result.options.features.max_features;
  for (const TypeSummary& s : result.types) {
    nlohmann::json t = {{"type", s.type},
                        {"pairs", s.pairs},
                        {"keypoints_per_image", s.keypoints_per_image},
                        {"repeatability", s.repeatability},
                        {"matching_score", s.matching_score},
                        {"mma", s.mma},
                        {"homography_accuracy", s.homography_accuracy},
                        {"extraction_ms", s.extraction_ms},
                        {"descriptor_bytes", s.descriptor_bytes}};
    for (const PairRecord& r : s.records) {
      const PairMetrics& m = r.metrics;
      t["pairs_detail"].push_back({{"sequence", r.sequence},
                                   {"target", r.target_index},
                                   {"reference_keypoints", m.reference_keypoints},
                                   {"target_keypoints", m.target_keypoints},
                                   {"matches", m.matches},
                                   {"correct_matches", m.correct_matches},
                                   {"repeatability", m.repeatability},
                                   {"matching_score", m.matching_score},
                                   {"mma", m.mma},
                                   {"homography_estimated", m.homography_estimated},
                                   {"corner_error_px", m.corner_error_px},
                                   {"homography_correct", m.homography_correct}});
    }
    j["types"].push_back(t);
  }
  return j;
}

std::string ToMarkdown(const FeatureEvalResult& result) {
  std::ostringstream out;
  out << std::fixed;
  out << "| type | kp/image | repeatability@3px | matching score | MMA@1 | MMA@3 | MMA@5 "
         "| homography@3px | ms/image | descriptor bytes |\n";
  out << "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n";
  for (const TypeSummary& s : result.types) {
    out << "| " << s.type << " | " << std::setprecision(0) << s.keypoints_per_image << " | "
        << std::setprecision(3) << s.repeatability << " | " << s.matching_score << " | "
        << s.mma[0] << " | " << s.mma[1] << " | " << s.mma[2] << " | " << s.homography_accuracy
        << " | " << std::setprecision(1) << s.extraction_ms << " | " << s.descriptor_bytes
        << " |\n";
  }
  return out.str();
}

}  // namespace duskmap
