#include "slam/registration/nndr_matcher.h"

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <unordered_map>

#include <Eigen/Core>
#include <opencv2/core/hal/hal.hpp>
#include <opencv2/flann.hpp>

#include "slam/core/check.h"

namespace duskmap {
namespace {

using RowMatrixF = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

void Offer(int index, double distance, TwoNearest* nn) {
  if (nn->best < 0 || distance < nn->best_distance) {
    nn->second = nn->best;
    nn->second_distance = nn->best_distance;
    nn->best = index;
    nn->best_distance = distance;
  } else if (nn->second < 0 || distance < nn->second_distance) {
    nn->second = index;
    nn->second_distance = distance;
  }
}

// Exact 2-NN on squared L2 through one matrix product:
// |q - t|^2 = |q|^2 + |t|^2 - 2 q.t, evaluated in blocks of query rows.
std::vector<TwoNearest> BruteForceFloat(const cv::Mat& query, const cv::Mat& train) {
  const Eigen::Map<const RowMatrixF> q(query.ptr<float>(), query.rows, query.cols);
  const Eigen::Map<const RowMatrixF> t(train.ptr<float>(), train.rows, train.cols);
  const Eigen::VectorXf train_norms = t.rowwise().squaredNorm();
  std::vector<TwoNearest> result(query.rows);
  constexpr int kBlock = 256;
  Eigen::MatrixXf dots;
  for (int start = 0; start < query.rows; start += kBlock) {
    const int rows = std::min(kBlock, query.rows - start);
    dots.noalias() = t * q.middleRows(start, rows).transpose();  // train x rows
    for (int r = 0; r < rows; ++r) {
      const float query_norm = q.row(start + r).squaredNorm();
      TwoNearest& nn = result[start + r];
      for (int j = 0; j < train.rows; ++j) {
        const double d = std::max(0.0f, query_norm + train_norms[j] - 2.0f * dots(j, r));
        Offer(j, d, &nn);
      }
    }
  }
  return result;
}

// 2-NN over rows of `words` 64-bit words (ORB/BRIEF: 4 words).
inline __attribute__((always_inline)) void ScanHammingWords(const uint64_t* q, int query_rows,
                                                            const uint64_t* t, int train_rows,
                                                            int words,
                                                            std::vector<TwoNearest>* result) {
  for (int i = 0; i < query_rows; ++i) {
    const uint64_t* a = q + static_cast<size_t>(i) * words;
    for (int j = 0; j < train_rows; ++j) {
      const uint64_t* b = t + static_cast<size_t>(j) * words;
      int distance = 0;
      for (int w = 0; w < words; ++w) distance += __builtin_popcountll(a[w] ^ b[w]);
      Offer(j, distance, &(*result)[i]);
    }
  }
}

// The same scan compiled with the POPCNT instruction (used when the CPU has it).
__attribute__((target("popcnt"))) void ScanHammingWordsPopcnt(
    const uint64_t* q, int query_rows, const uint64_t* t, int train_rows, int words,
    std::vector<TwoNearest>* result) {
  ScanHammingWords(q, query_rows, t, train_rows, words, result);
}

std::vector<TwoNearest> BruteForceBinary(const cv::Mat& query, const cv::Mat& train) {
  std::vector<TwoNearest> result(query.rows);
  if (query.cols % 8 == 0) {  // rows of whole 64-bit words
    const int words = query.cols / 8;
    std::vector<uint64_t> q(static_cast<size_t>(query.rows) * words);
    std::vector<uint64_t> t(static_cast<size_t>(train.rows) * words);
    std::memcpy(q.data(), query.data, q.size() * sizeof(uint64_t));
    std::memcpy(t.data(), train.data, t.size() * sizeof(uint64_t));
    if (__builtin_cpu_supports("popcnt")) {
      ScanHammingWordsPopcnt(q.data(), query.rows, t.data(), train.rows, words, &result);
    } else {
      ScanHammingWords(q.data(), query.rows, t.data(), train.rows, words, &result);
    }
    return result;
  }
  for (int i = 0; i < query.rows; ++i) {
    const uchar* a = query.ptr<uchar>(i);
    for (int j = 0; j < train.rows; ++j) {
      Offer(j, cv::hal::normHamming(a, train.ptr<uchar>(j), query.cols), &result[i]);
    }
  }
  return result;
}

// Exact 2-NN on the L1 of the byte values (binary_distance byte_l1).
std::vector<TwoNearest> BruteForceByteL1(const cv::Mat& query, const cv::Mat& train) {
  std::vector<TwoNearest> result(query.rows);
  for (int i = 0; i < query.rows; ++i) {
    const uint8_t* a = query.ptr<uint8_t>(i);
    for (int j = 0; j < train.rows; ++j) {
      Offer(j, ByteL1Distance(a, train.ptr<uint8_t>(j), query.cols), &result[i]);
    }
  }
  return result;
}

std::vector<TwoNearest> KdTreeFloat(const NndrMatcherOptions& options, const cv::Mat& query,
                                    const cv::Mat& train) {
  // OpenCV's FLANN draws its random split choices from std::rand(); seeding
  // it here makes the trees (and so the matches) reproducible.
  std::srand(static_cast<unsigned>(options.random_seed));
  cv::flann::Index index(train, cv::flann::KDTreeIndexParams(options.kd_trees),
                         cvflann::FLANN_DIST_L2);
  cv::Mat indices(query.rows, 2, CV_32S);
  cv::Mat distances(query.rows, 2, CV_32F);
  index.knnSearch(query, indices, distances, 2, cv::flann::SearchParams(options.kd_checks));
  std::vector<TwoNearest> result(query.rows);
  for (int i = 0; i < query.rows; ++i) {
    for (int k = 0; k < 2; ++k) {
      const int j = indices.at<int>(i, k);
      if (j >= 0 && j < train.rows) Offer(j, distances.at<float>(i, k), &result[i]);
    }
  }
  return result;
}

bool UseKdTree(const NndrMatcherOptions& options, DescriptorKind kind, int train_rows) {
  if (kind != DescriptorKind::kFloat || train_rows < 2) return false;
  switch (options.search) {
    case NndrSearch::kBruteForce: return false;
    case NndrSearch::kKdTree: return true;
    case NndrSearch::kAuto: return train_rows >= options.kd_min_train_size;
  }
  return false;
}

}  // namespace

void NndrMatcherOptions::Check() const {
  SLAM_THROW_IF_NOT(ConfigError, float_ratio > 0.0 && float_ratio <= 1.0)
      << "NndrMatcherOptions.float_ratio: must be in (0, 1], got " << float_ratio;
  SLAM_THROW_IF_NOT(ConfigError, binary_ratio > 0.0 && binary_ratio <= 1.0)
      << "NndrMatcherOptions.binary_ratio: must be in (0, 1], got " << binary_ratio;
  SLAM_THROW_IF_NOT(ConfigError, kd_min_train_size >= 2)
      << "NndrMatcherOptions.kd_min_train_size: must be >= 2, got " << kd_min_train_size;
  SLAM_THROW_IF_NOT(ConfigError, kd_trees >= 1)
      << "NndrMatcherOptions.kd_trees: must be >= 1, got " << kd_trees;
  SLAM_THROW_IF_NOT(ConfigError, kd_checks >= 1)
      << "NndrMatcherOptions.kd_checks: must be >= 1, got " << kd_checks;
}

double DescriptorDistance(const cv::Mat& a, int row_a, const cv::Mat& b, int row_b,
                          DescriptorKind kind) {
  if (kind == DescriptorKind::kBinary) {
    return cv::hal::normHamming(a.ptr<uchar>(row_a), b.ptr<uchar>(row_b), a.cols);
  }
  return cv::hal::normL2Sqr_(a.ptr<float>(row_a), b.ptr<float>(row_b), a.cols);
}

void CheckFeatures(const FrameFeatures& features, const char* what) {
  if (features.empty() && features.descriptors.empty()) return;
  SLAM_THROW_IF_NOT(InputError, features.descriptors.rows == static_cast<int>(features.size()))
      << what << ": " << features.descriptors.rows << " descriptor rows for "
      << features.size() << " keypoints";
  const int expected_type = features.kind == DescriptorKind::kFloat ? CV_32F : CV_8U;
  SLAM_THROW_IF_NOT(InputError, features.descriptors.type() == expected_type)
      << what << ": descriptor type " << features.descriptors.type() << " does not match its "
      << (features.kind == DescriptorKind::kFloat ? "float" : "binary") << " kind";
  SLAM_THROW_IF_NOT(InputError, features.descriptors.isContinuous())
      << what << ": descriptors must be a continuous matrix";
  SLAM_THROW_IF_NOT(InputError, features.points_in_camera.empty() ||
                                    features.points_in_camera.size() == features.size())
      << what << ": " << features.points_in_camera.size() << " 3D points for "
      << features.size() << " keypoints";
}

void CheckComparable(const FrameFeatures& a, const FrameFeatures& b) {
  if (a.empty() || b.empty()) return;
  SLAM_THROW_IF_NOT(InputError, a.kind == b.kind && a.descriptors.type() == b.descriptors.type())
      << "features: cannot match float descriptors against binary ones";
  SLAM_THROW_IF_NOT(InputError, a.descriptors.cols == b.descriptors.cols)
      << "features: descriptor widths differ (" << a.descriptors.cols << " vs "
      << b.descriptors.cols << ")";
}

NndrMatcher::NndrMatcher(NndrMatcherOptions options) : options_(options) { options_.Check(); }

std::vector<cv::DMatch> NndrMatcher::Match(const FrameFeatures& query, const cv::Size&,
                                           const FrameFeatures& train, const cv::Size&) const {
  CheckFeatures(query, "query features");
  CheckFeatures(train, "map node features");
  std::vector<cv::DMatch> matches;
  if (query.empty() || train.empty()) return matches;
  CheckComparable(query, train);

  const std::vector<TwoNearest> neighbours =
      UseKdTree(options_, train.kind, train.descriptors.rows)
          ? KdTreeFloat(options_, query.descriptors, train.descriptors)
      : train.kind == DescriptorKind::kFloat
          ? BruteForceFloat(query.descriptors, train.descriptors)
      : options_.binary_distance == BinaryDistance::kByteL1
          ? BruteForceByteL1(query.descriptors, train.descriptors)
          : BruteForceBinary(query.descriptors, train.descriptors);
  const double ratio = options_.RatioFor(train.kind);
  for (int i = 0; i < static_cast<int>(neighbours.size()); ++i) {
    const TwoNearest& nn = neighbours[i];
    // Without a second neighbour (a one-feature map node) the ratio is undefined.
    if (nn.best < 0 || nn.second < 0) continue;
    if (nn.best_distance < ratio * nn.second_distance) {
      matches.emplace_back(i, nn.best, static_cast<float>(nn.best_distance));
    }
  }
  if (!options_.unique) return matches;
  std::unordered_map<int, int> uses;
  for (const cv::DMatch& m : matches) ++uses[m.trainIdx];
  std::vector<cv::DMatch> unique;
  unique.reserve(matches.size());
  for (const cv::DMatch& m : matches) {
    if (uses[m.trainIdx] == 1) unique.push_back(m);
  }
  return unique;
}

}  // namespace duskmap
