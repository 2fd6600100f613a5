#include "slam/features/eval/sequence_eval.h"

#include <algorithm>
#include <filesystem>
#include <iomanip>
#include <map>
#include <sstream>

#include "slam/core/check.h"
#include "slam/features/eval/eval_image.h"
#include "slam/core/timer.h"
#include "slam/features/feature_factory.h"

namespace duskmap {
namespace fs = std::filesystem;
namespace {

double Mean(double sum, int n) { return n == 0 ? 0.0 : sum / n; }

struct ExtractedImage {
  std::string file;  // the file's name
  cv::Size size;
  FrameFeatures features;
};

TypeSummary EvaluateType(const std::vector<ImageSequence>& sequences, const FeatureEvalOptions& options,
                         const std::string& type) {
  FeatureOptions feature_options = options.features;
  feature_options.type = type;
  const auto extractor = CreateFeatureExtractor(feature_options);
  TypeSummary s;
  s.type = type;
  double keypoints = 0.0, time_ms = 0.0, homographies = 0.0;
  int images = 0;
  for (const ImageSequence& seq : sequences) {
    std::map<int, ExtractedImage> extracted;  // by index, each image once
    const auto image = [&](int index) -> const ExtractedImage& {
      auto it = extracted.find(index);
      if (it != extracted.end()) return it->second;
      const SequenceImage* file = seq.Image(index);
      SLAM_CHECK(file != nullptr);
      const cv::Mat pixels = ReadEvalImage(file->path);
      Stopwatch watch;
      ExtractedImage e{fs::path(file->path).filename().string(), pixels.size(), extractor->Extract(pixels)};
      time_ms += watch.ElapsedMs();
      keypoints += static_cast<double>(e.features.size());
      ++images;
      if (!e.features.empty()) s.descriptor_bytes = static_cast<int>(e.features.DescriptorBytes());
      return extracted.emplace(index, std::move(e)).first->second;
    };
    for (const SequencePair& pair : seq.pairs) {
      const ExtractedImage& reference = image(pair.first_index);
      const ExtractedImage& target = image(pair.second_index);
      SLAM_THROW_IF_NOT(InputError, seq.layout != SequenceLayout::kStatic || reference.size == target.size)
          << seq.Image(pair.second_index)->path << ": " << target.size.width << "x" << target.size.height
          << ", but " << reference.file << " is " << reference.size.width << "x" << reference.size.height
          << " (a fixed camera's images have one size)";
      PairRecord record;
      record.sequence = seq.name;
      record.reference_index = pair.first_index;
      record.target_index = pair.second_index;
      record.reference_image = reference.file;
      record.target_image = target.file;
      record.metrics = EvaluatePair(reference.features, reference.size, target.features, target.size,
                                    pair.second_from_first, options.metrics);
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

void FeatureEvalOptions::Check() const {
  SLAM_THROW_IF_NOT(ConfigError, !types.empty()) << "features eval: no feature type given";
  for (const std::string& t : types) {
    FeatureOptions o = features;
    o.type = t;
    o.Check();
  }
  metrics.Check();
}

FeatureEvalResult EvaluateFeatures(const std::vector<ImageSequence>& sequences,
                                   const FeatureEvalOptions& options) {
  options.Check();
  FeatureEvalResult result;
  result.options = options;
  if (!sequences.empty()) result.layout = sequences.front().layout;
  for (const auto& seq : sequences) result.sequences.push_back(seq.name);
  for (const std::string& type : options.types) {
    result.types.push_back(EvaluateType(sequences, options, type));
  }
  return result;
}

nlohmann::json ToJson(const FeatureEvalResult& result) {
  nlohmann::json j;
  j["layout"] = SequenceLayoutName(result.layout);
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
                                   {"reference", r.reference_index},
                                   {"target", r.target_index},
                                   {"reference_image", r.reference_image},
                                   {"target_image", r.target_image},
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
  out << "\nPer pair (reference-target, image indices as the sequence names them):\n\n"
         "| type | sequence | pair | keypoints | matches | correct | repeatability@3px | matching score "
         "| MMA@1 | MMA@3 | MMA@5 | corner error px | homography@3px |\n"
         "| --- | --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | --- |\n";
  for (const TypeSummary& s : result.types) {
    for (const PairRecord& r : s.records) {
      const PairMetrics& m = r.metrics;
      out << "| " << s.type << " | " << r.sequence << " | " << r.reference_index << "-" << r.target_index
          << " | " << m.reference_keypoints << " / " << m.target_keypoints << " | " << m.matches << " | "
          << m.correct_matches << " | " << std::setprecision(3) << m.repeatability << " | "
          << m.matching_score << " | " << m.mma[0] << " | " << m.mma[1] << " | " << m.mma[2] << " | ";
      if (m.homography_estimated) {
        out << std::setprecision(2) << m.corner_error_px;
      } else {
        out << "–";
      }
      out << " | " << (m.homography_correct ? "yes" : "no") << " |\n";
    }
  }
  return out.str();
}

}  // namespace duskmap
