#include "slam/features/eval/epipolar_eval.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <memory>
#include <sstream>

#include <opencv2/calib3d.hpp>
#include <opencv2/features2d.hpp>
#include <opencv2/imgcodecs.hpp>

#include "slam/core/check.h"
#include "slam/core/input_file.h"
#include "slam/features/eval/eval_image.h"
#include "slam/core/timer.h"
#include "slam/features/feature_factory.h"

namespace duskmap {
namespace {
namespace fs = std::filesystem;

constexpr double kInfinity = std::numeric_limits<double>::infinity();

constexpr const char* kPairImageExtensions[] = {".png", ".jpg", ".jpeg", ".ppm", ".bmp"};
constexpr const char* kPairImagePattern = "{png,jpg,jpeg,ppm,bmp}";

bool IsImageName(const fs::path& path) {
  const std::string extension = path.extension().string();
  for (const char* e : kPairImageExtensions) {
    if (extension == e) return true;
  }
  return extension == ".pgm";
}

// The image "<stem>.*" of a pair folder (png, jpg, jpeg, ppm, bmp); "" when none.
std::string FindImage(const fs::path& directory, const std::string& stem) {
  for (const char* extension : kPairImageExtensions) {
    const fs::path path = directory / (stem + extension);
    std::error_code error;
    if (fs::is_regular_file(path, error)) return path.string();
  }
  return "";
}

std::vector<fs::path> SortedSubfolders(const fs::path& root) {
  std::vector<fs::path> folders;
  std::error_code error;
  for (fs::directory_iterator it(root, error); !error && it != fs::directory_iterator();
       it.increment(error)) {
    std::error_code type_error;
    if (it->is_directory(type_error)) folders.push_back(it->path());
  }
  std::sort(folders.begin(), folders.end());
  return folders;
}

double Median(std::vector<double> values) {
  if (values.empty()) return kInfinity;
  const size_t middle = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + middle, values.end());
  if (values.size() % 2 == 1) return values[middle];
  const double upper = values[middle];
  const double lower = *std::max_element(values.begin(), values.begin() + middle);
  return 0.5 * (lower + upper);
}

// Ratio-test matches first -> second.
std::vector<std::pair<cv::Point2f, cv::Point2f>> RatioMatches(const FrameFeatures& first,
                                                               const FrameFeatures& second,
                                                               double ratio) {
  std::vector<std::pair<cv::Point2f, cv::Point2f>> matches;
  if (first.descriptors.empty() || second.descriptors.rows < 2) return matches;
  const int norm = first.kind == DescriptorKind::kBinary ? cv::NORM_HAMMING : cv::NORM_L2;
  cv::BFMatcher matcher(norm);
  std::vector<std::vector<cv::DMatch>> knn;
  matcher.knnMatch(first.descriptors, second.descriptors, knn, 2);
  for (const std::vector<cv::DMatch>& m : knn) {
    if (m.size() == 2 && m[0].distance < ratio * m[1].distance) {
      matches.emplace_back(first.keypoints[m[0].queryIdx].pt, second.keypoints[m[0].trainIdx].pt);
    }
  }
  return matches;
}

RgbdFrame PairFrame(const cv::Mat& image, const CorrespondencePair& pair, const std::string& path) {
  RgbdFrame frame;
  frame.bgr = image;
  frame.camera.width = image.cols;
  frame.camera.height = image.rows;
  frame.session = pair.name;
  frame.image_name = fs::path(path).filename().string();
  frame.image_file = path;
  return frame;
}

void CheckInside(const CorrespondencePair& pair, const cv::Size& first, const cv::Size& second) {
  for (size_t i = 0; i < pair.correspondences.size(); ++i) {
    const cv::Vec4d& c = pair.correspondences[i];
    const bool inside = c[0] >= -0.5 && c[1] >= -0.5 && c[0] <= first.width - 0.5 &&
                        c[1] <= first.height - 0.5 && c[2] >= -0.5 && c[3] >= -0.5 &&
                        c[2] <= second.width - 0.5 && c[3] <= second.height - 0.5;
    SLAM_THROW_IF_NOT(InputError, inside)
        << (fs::path(pair.first_path).parent_path() / "corrs.txt").string() << ":" << i + 1
        << ": correspondence (" << c[0] << ", " << c[1] << ") -> (" << c[2] << ", " << c[3]
        << ") lies outside the images (" << first.width << "x" << first.height << ", "
        << second.width << "x" << second.height << ")";
  }
}

}  // namespace

bool IsCorrespondencePairFolder(const std::string& directory) {
  std::error_code error;
  if (fs::is_regular_file(fs::path(directory) / "corrs.txt", error)) return true;
  if (FindImage(directory, "01").empty() && FindImage(directory, "02").empty()) return false;
  for (fs::directory_iterator it(directory, error); !error && it != fs::directory_iterator(); it.increment(error)) {
    const std::string stem = it->path().stem().string();
    if (stem != "01" && stem != "02" && IsImageName(it->path())) return false;
  }
  return true;
}

CorrespondencePair ReadCorrespondencePair(const std::string& directory, const std::string& name,
                                          const std::string& category) {
  CorrespondencePair pair;
  pair.name = name;
  pair.category = category;
  pair.first_path = FindImage(directory, "01");
  pair.second_path = FindImage(directory, "02");
  for (const char* stem : {"01", "02"}) {
    SLAM_THROW_IF_NOT(InputError, !FindImage(directory, stem).empty())
        << (fs::path(directory) / stem).string() << "." << kPairImagePattern
        << ": missing (a pair folder holds 01.*, 02.* and corrs.txt)";
  }
  const std::string corrs = (fs::path(directory) / "corrs.txt").string();
  RefuseNonRegularFile(corrs);  // before opening: a FIFO would block
  std::ifstream in(corrs);
  SLAM_THROW_IF_NOT(InputError, in.good())
      << corrs << ": missing (the pair's correspondences; a fixed camera's images named 01, 02: --layout static)";
  int line_number = 0;
  for (std::string line; std::getline(in, line);) {
    ++line_number;
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    std::istringstream row(line);
    cv::Vec4d c;
    std::string rest;
    const bool four = static_cast<bool>(row >> c[0] >> c[1] >> c[2] >> c[3]) && !(row >> rest);
    SLAM_THROW_IF_NOT(InputError, four && std::isfinite(c[0]) && std::isfinite(c[1]) &&
                                      std::isfinite(c[2]) && std::isfinite(c[3]))
        << corrs << ":" << line_number << ": expected four numbers 'x1 y1 x2 y2', got '" << line << "'";
    pair.correspondences.push_back(c);
  }
  SLAM_THROW_IF_NOT(InputError, !pair.correspondences.empty()) << corrs << ": no correspondence";
  return pair;
}

std::vector<CorrespondencePair> FindCorrespondencePairs(const std::string& root) {
  if (IsCorrespondencePairFolder(root)) {
    return {ReadCorrespondencePair(root, fs::path(root).filename().string(), "")};
  }
  std::vector<CorrespondencePair> pairs;
  for (const fs::path& folder : SortedSubfolders(root)) {
    const std::string name = folder.filename().string();
    if (IsCorrespondencePairFolder(folder.string())) {
      pairs.push_back(ReadCorrespondencePair(folder.string(), name, ""));
      continue;
    }
    for (const fs::path& inner : SortedSubfolders(folder)) {
      if (!IsCorrespondencePairFolder(inner.string())) continue;
      pairs.push_back(ReadCorrespondencePair(inner.string(), name + "/" + inner.filename().string(), name));
    }
  }
  return pairs;
}

std::vector<CorrespondencePair> SelectCorrespondencePairs(const std::vector<CorrespondencePair>& pairs,
                                                          const std::vector<PairSelector>& selectors) {
  std::vector<CorrespondencePair> selected;
  for (const PairSelector& selector : selectors) {
    const auto it = std::find_if(pairs.begin(), pairs.end(),
                                 [&](const CorrespondencePair& p) { return p.name == selector.text; });
    if (it != pairs.end()) {
      selected.push_back(*it);
      continue;
    }
    std::string names;
    for (size_t i = 0; i < pairs.size() && i < 10; ++i) names += (i == 0 ? "" : ", ") + pairs[i].name;
    if (pairs.size() > 10) names += ", ... (" + std::to_string(pairs.size()) + " in all)";
    SLAM_THROW(ConfigError) << selector.origin << ": pair '" << selector.text << "' does not exist (pairs: "
                            << names << ")";
  }
  return selected;
}

double SymmetricEpipolarDistancePx(const cv::Matx33d& f, const cv::Point2d& x1, const cv::Point2d& x2) {
  const cv::Vec3d p1(x1.x, x1.y, 1.0);
  const cv::Vec3d p2(x2.x, x2.y, 1.0);
  const cv::Vec3d line2 = f * p1;            // in the second image
  const cv::Vec3d line1 = f.t() * p2;        // in the first image
  const double residual = std::abs(p2.dot(line2));
  const double norm2 = std::hypot(line2[0], line2[1]);
  const double norm1 = std::hypot(line1[0], line1[1]);
  if (norm1 <= 0.0 || norm2 <= 0.0) return kInfinity;
  return 0.5 * (residual / norm2 + residual / norm1);
}

void EpipolarEvalOptions::Check() const {
  SLAM_THROW_IF_NOT(ConfigError, !types.empty()) << "features eval: no feature type";
  SLAM_THROW_IF_NOT(ConfigError, float_ratio > 0.0 && float_ratio <= 1.0 && binary_ratio > 0.0 &&
                                     binary_ratio <= 1.0)
      << "features eval: ratio-test ratios must be in (0, 1]";
  SLAM_THROW_IF_NOT(ConfigError, ransac_threshold_px > 0.0 && ransac_confidence > 0.0 &&
                                     ransac_confidence < 1.0 && ransac_max_iterations >= 1)
      << "features eval: RANSAC threshold > 0, confidence in (0, 1) and iterations >= 1";
  for (double t : solved_px) {
    SLAM_THROW_IF_NOT(ConfigError, t > 0.0) << "features eval: solved thresholds must be > 0 px";
  }
}

EpipolarEvalResult EvaluateOnCorrespondencePairs(const std::vector<CorrespondencePair>& pairs,
                                                 const EpipolarEvalOptions& options) {
  options.Check();
  EpipolarEvalResult result;
  result.options = options;
  for (const CorrespondencePair& pair : pairs) result.pairs.push_back(pair.name);
  std::vector<std::pair<cv::Mat, cv::Mat>> images;
  for (const CorrespondencePair& pair : pairs) {
    images.emplace_back(ReadEvalImage(pair.first_path), ReadEvalImage(pair.second_path));
    CheckInside(pair, images.back().first.size(), images.back().second.size());
  }
  for (const std::string& type : options.types) {
    FeatureOptions feature_options = options.features;
    feature_options.type = type;
    const std::unique_ptr<FeatureExtractor> extractor = CreateFeatureExtractor(feature_options);
    EpipolarTypeSummary summary;
    summary.type = type;
    double extraction_ms = 0.0;
    std::vector<double> errors;
    for (size_t p = 0; p < pairs.size(); ++p) {
      const CorrespondencePair& pair = pairs[p];
      EpipolarPairRecord record;
      record.pair = pair.name;
      record.category = pair.category;
      Stopwatch watch;
      const FrameFeatures first = extractor->ExtractFrame(PairFrame(images[p].first, pair, pair.first_path));
      const FrameFeatures second =
          extractor->ExtractFrame(PairFrame(images[p].second, pair, pair.second_path));
      extraction_ms += watch.ElapsedMs();
      record.keypoints_first = static_cast<int>(first.size());
      record.keypoints_second = static_cast<int>(second.size());
      const auto matches = RatioMatches(
          first, second, first.kind == DescriptorKind::kBinary ? options.binary_ratio : options.float_ratio);
      record.matches = static_cast<int>(matches.size());
      record.median_error_px = kInfinity;
      if (matches.size() >= 8) {
        std::vector<cv::Point2f> points1, points2;
        for (const auto& [a, b] : matches) {
          points1.push_back(a);
          points2.push_back(b);
        }
        cv::Mat inliers;
        cv::Mat f;
        try {
          f = cv::findFundamentalMat(points1, points2, cv::USAC_MAGSAC, options.ransac_threshold_px,
                                     options.ransac_confidence, options.ransac_max_iterations, inliers);
        } catch (const cv::Exception&) {
          f.release();
        }
        if (f.rows == 3 && f.cols == 3) {  // the 7-point solver may return up to three stacked
          record.estimated = true;
          record.inliers = cv::countNonZero(inliers);
          const cv::Matx33d fundamental(f);
          std::vector<double> distances;
          for (const cv::Vec4d& c : pair.correspondences) {
            distances.push_back(
                SymmetricEpipolarDistancePx(fundamental, {c[0], c[1]}, {c[2], c[3]}));
          }
          record.median_error_px = Median(distances);
        }
      }
      ++summary.pairs;
      ++summary.pairs_by_category[pair.category];
      std::array<int, 3>& by_category = summary.solved_by_category[pair.category];
      for (size_t t = 0; t < options.solved_px.size(); ++t) {
        const bool solved = record.median_error_px <= options.solved_px[t];
        summary.solved[t] += solved;
        by_category[t] += solved;
      }
      errors.push_back(record.median_error_px);
      summary.records.push_back(record);
    }
    summary.median_error_px = Median(errors);
    summary.extraction_ms = pairs.empty() ? 0.0 : extraction_ms / (2.0 * pairs.size());
    result.types.push_back(std::move(summary));
  }
  return result;
}

nlohmann::json ToJson(const EpipolarEvalResult& result) {
  const auto number = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); };
  nlohmann::json types = nlohmann::json::array();
  for (const EpipolarTypeSummary& t : result.types) {
    nlohmann::json records = nlohmann::json::array();
    for (const EpipolarPairRecord& r : t.records) {
      records.push_back({{"pair", r.pair},
                         {"category", r.category},
                         {"keypoints", {r.keypoints_first, r.keypoints_second}},
                         {"matches", r.matches},
                         {"inliers", r.inliers},
                         {"estimated", r.estimated},
                         {"median_error_px", number(r.median_error_px)}});
    }
    nlohmann::json categories = nlohmann::json::object();
    for (const auto& [category, solved] : t.solved_by_category) {
      categories[category.empty() ? "-" : category] = {{"pairs", t.pairs_by_category.at(category)},
                                                       {"solved", solved}};
    }
    types.push_back({{"type", t.type},
                     {"pairs", t.pairs},
                     {"solved", t.solved},
                     {"categories", categories},
                     {"median_error_px", number(t.median_error_px)},
                     {"extraction_ms", t.extraction_ms},
                     {"records", records}});
  }
  return {{"layout", "pairs"},
          {"pairs", result.pairs},
          {"solved_px", result.options.solved_px},
          {"ratio", {{"float", result.options.float_ratio}, {"binary", result.options.binary_ratio}}},
          {"ransac", {{"method", "USAC_MAGSAC"},
                      {"threshold_px", result.options.ransac_threshold_px},
                      {"confidence", result.options.ransac_confidence},
                      {"max_iterations", result.options.ransac_max_iterations}}},
          {"types", types}};
}

std::string ToMarkdown(const EpipolarEvalResult& result) {
  const auto& px = result.options.solved_px;
  std::ostringstream out;
  out << std::fixed << std::setprecision(1);
  out << "| type | pairs | solved @" << px[0] << " px | @" << px[1] << " px | @" << px[2]
      << " px | median error px | ms/image |\n| --- | ---: | ---: | ---: | ---: | ---: | ---: |\n";
  for (const EpipolarTypeSummary& t : result.types) {
    out << "| " << t.type << " | " << t.pairs << " | " << t.solved[0] << " | " << t.solved[1] << " | "
        << t.solved[2] << " | ";
    if (std::isfinite(t.median_error_px)) {
      out << std::setprecision(2) << t.median_error_px << std::setprecision(1);
    } else {
      out << "–";
    }
    out << " | " << t.extraction_ms << " |\n";
  }
  out << "\nSolved per category (@" << px[0] << " / " << px[1] << " / " << px[2]
      << " px, of the category's pairs):\n\n| type | category | pairs | solved |\n"
         "| --- | --- | ---: | --- |\n";
  for (const EpipolarTypeSummary& t : result.types) {
    for (const auto& [category, solved] : t.solved_by_category) {
      out << "| " << t.type << " | " << (category.empty() ? "-" : category) << " | "
          << t.pairs_by_category.at(category) << " | " << solved[0] << " / " << solved[1] << " / "
          << solved[2] << " |\n";
    }
  }
  out << "\nPer pair:\n\n| type | pair | keypoints | matches | inliers | median error px | solved @"
      << px[0] << " / " << px[1] << " / " << px[2] << " px |\n| --- | --- | ---: | ---: | ---: | ---: | --- |\n";
  for (const EpipolarTypeSummary& t : result.types) {
    for (const EpipolarPairRecord& r : t.records) {
      out << "| " << t.type << " | " << r.pair << " | " << r.keypoints_first << " / " << r.keypoints_second
          << " | " << r.matches << " | " << r.inliers << " | ";
      if (std::isfinite(r.median_error_px)) {
        out << std::setprecision(2) << r.median_error_px << std::setprecision(1);
      } else {
        out << "–";
      }
      out << " |";
      for (size_t k = 0; k < px.size(); ++k) {
        out << (k == 0 ? " " : " / ") << (r.median_error_px <= px[k] ? "yes" : "no");
      }
      out << " |\n";
    }
  }
  return out.str();
}

}  // namespace duskmap
