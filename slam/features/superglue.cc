#include "slam/features/superglue.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>

#include "slam/core/check.h"
#include "slam/core/input_file.h"

namespace duskmap {
namespace {

constexpr int kDescriptorDim = 256;

// The network input of one side: keypoints, scores, descriptors (channels first).
struct SideBlobs {
  cv::Mat keypoints;    // 1xMx2
  cv::Mat scores;       // 1xM
  cv::Mat descriptors;  // 1x256xM
};

SideBlobs PrepareSide(const FrameFeatures& f, const cv::Size& image, const char* side,
                      const std::string& model) {
  const int m = static_cast<int>(f.keypoints.size());
  SLAM_THROW_IF_NOT(InputError, f.descriptors.rows == m)
      << model << ": SuperGlue " << side << " features have " << f.descriptors.rows
      << " descriptor rows for " << m << " keypoints";
  SLAM_THROW_IF_NOT(InputError, f.descriptors.type() == CV_32F && f.descriptors.cols == kDescriptorDim)
      << model << ": SuperGlue needs 256-D float (SuperPoint) descriptors, the " << side
      << " features have " << f.descriptors.cols << " columns of type " << f.descriptors.type();
  SLAM_THROW_IF_NOT(InputError, image.width > 0 && image.height > 0)
      << model << ": SuperGlue needs the " << side << " image size, got " << image.width << "x"
      << image.height;
  SideBlobs blobs;
  blobs.keypoints = NormalizeSuperGlueKeypoints(f.keypoints, image);
  const int scores_size[2] = {1, m};
  blobs.scores.create(2, scores_size, CV_32F);
  for (int i = 0; i < m; ++i) blobs.scores.ptr<float>(0)[i] = f.keypoints[i].response;
  const int desc_size[3] = {1, kDescriptorDim, m};
  blobs.descriptors.create(3, desc_size, CV_32F);
  cv::Mat channels_first(kDescriptorDim, m, CV_32F, blobs.descriptors.ptr<float>());
  cv::transpose(f.descriptors, channels_first);
  return blobs;
}

}  // namespace

void SuperGlueOptions::Check() const {
  SLAM_THROW_IF_NOT(ConfigError, match_threshold >= 0.0 && match_threshold < 1.0)
      << "superglue.match_threshold: must be in [0, 1), got " << match_threshold;
}

std::vector<cv::DMatch> DecodeSuperGlueAssignment(const cv::Mat& log_assignment,
                                                  double match_threshold) {
  SLAM_CHECK(log_assignment.type() == CV_32F && log_assignment.dims == 2);
  SLAM_CHECK(log_assignment.rows >= 1 && log_assignment.cols >= 1);
  const int m = log_assignment.rows - 1, n = log_assignment.cols - 1;
  constexpr float kLowest = -std::numeric_limits<float>::infinity();
  std::vector<int> best_col(m, -1), best_row(n, -1);
  std::vector<float> row_max(m, kLowest), col_max(n, kLowest);
  for (int i = 0; i < m; ++i) {
    const float* row = log_assignment.ptr<float>(i);
    for (int j = 0; j < n; ++j) {
      const float s = row[j];
      if (!std::isfinite(s)) continue;
      if (s > row_max[i]) {  // strict: ties keep the lowest column
        row_max[i] = s;
        best_col[i] = j;
      }
      if (s > col_max[j]) {  // rows visited in order: ties keep the lowest row
        col_max[j] = s;
        best_row[j] = i;
      }
    }
  }
  std::vector<cv::DMatch> matches;
  for (int i = 0; i < m; ++i) {
    const int j = best_col[i];
    if (j < 0 || best_row[j] != i) continue;
    const double confidence = std::exp(static_cast<double>(row_max[i]));
    if (!(confidence > match_threshold)) continue;
    matches.emplace_back(i, j, static_cast<float>(1.0 - confidence));
  }
  return matches;
}

cv::Mat NormalizeSuperGlueKeypoints(const std::vector<cv::KeyPoint>& keypoints,
                                    const cv::Size& image) {
  const int m = static_cast<int>(keypoints.size());
  const int size[3] = {1, m, 2};
  cv::Mat blob(3, size, CV_32F);
  const float cx = image.width / 2.0f, cy = image.height / 2.0f;
  const float scale = 0.7f * static_cast<float>(std::max(image.width, image.height));
  float* p = blob.ptr<float>();
  for (int i = 0; i < m; ++i) {
    p[2 * i] = (keypoints[i].pt.x - cx) / scale;
    p[2 * i + 1] = (keypoints[i].pt.y - cy) / scale;
  }
  return blob;
}

void SuperGlueLogMarginals(int m, int n, cv::Mat* log_mu, cv::Mat* log_nu) {
  SLAM_CHECK(m >= 1 && n >= 1);
  const int mu_size[3] = {1, m + 1, 1}, nu_size[3] = {1, n + 1, 1};
  log_mu->create(3, mu_size, CV_32F);
  log_nu->create(3, nu_size, CV_32F);
  float* mu = log_mu->ptr<float>();
  float* nu = log_nu->ptr<float>();
  std::fill(mu, mu + m, 0.0f);
  std::fill(nu, nu + n, 0.0f);
  mu[m] = static_cast<float>(std::log(static_cast<double>(n)));
  nu[n] = static_cast<float>(std::log(static_cast<double>(m)));
}

SuperGlueMatcher::SuperGlueMatcher(const SuperGlueOptions& options) : options_(options) {
  options_.Check();
  const std::string& path = options_.model_path;
  SLAM_THROW_IF_NOT(InputError, !path.empty())
      << "superglue.model_path: no ONNX model given (see docs/features.md)";
  RefuseNonRegularFile(path);  // before opening: a FIFO would block
  SLAM_THROW_IF_NOT(InputError, std::ifstream(path).good()) << path << ": SuperGlue ONNX model not found";
  try {
    net_ = cv::dnn::readNetFromONNX(path);
  } catch (const cv::Exception&) {
    SLAM_THROW(InputError) << path << ": not a readable ONNX model";
  }
  SLAM_THROW_IF_NOT(InputError, !net_.empty()) << path << ": empty network";
  // OpenCV 4.6 folds a constant scale that follows a two-input MatMul into
  // the MatMul layer and then drops it (q.k / sqrt(d) comes out unscaled);
  // without fusion every layer runs as written.
  net_.enableFusion(false);
  // Validate the contract once on a small pair (3 and 2 keypoints).
  FrameFeatures a, b;
  for (int i = 0; i < 3; ++i) a.keypoints.emplace_back(cv::Point2f(4.0f * i, 2.0f), 8.0f, -1.0f, 0.5f);
  for (int i = 0; i < 2; ++i) b.keypoints.emplace_back(cv::Point2f(2.0f, 4.0f * i), 8.0f, -1.0f, 0.5f);
  a.descriptors = cv::Mat(3, kDescriptorDim, CV_32F, cv::Scalar(1.0f / 16.0f));
  b.descriptors = cv::Mat(2, kDescriptorDim, CV_32F, cv::Scalar(1.0f / 16.0f));
  LogAssignment(a, cv::Size(16, 16), b, cv::Size(16, 16));
}

cv::Mat SuperGlueMatcher::LogAssignment(const FrameFeatures& query, const cv::Size& query_image,
                                        const FrameFeatures& train,
                                        const cv::Size& train_image) const {
  const std::string& path = options_.model_path;
  const SideBlobs s0 = PrepareSide(query, query_image, "query", path);
  const SideBlobs s1 = PrepareSide(train, train_image, "train", path);
  const int m = static_cast<int>(query.size()), n = static_cast<int>(train.size());
  SLAM_THROW_IF_NOT(InputError, m >= 1 && n >= 1)
      << path << ": SuperGlue needs keypoints on both sides, got " << m << " and " << n;
  cv::Mat log_mu, log_nu;
  SuperGlueLogMarginals(m, n, &log_mu, &log_nu);
  cv::Mat out;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    try {
      net_.setInput(s0.keypoints, "keypoints0");
      net_.setInput(s0.scores, "scores0");
      net_.setInput(s0.descriptors, "descriptors0");
      net_.setInput(s1.keypoints, "keypoints1");
      net_.setInput(s1.scores, "scores1");
      net_.setInput(s1.descriptors, "descriptors1");
      net_.setInput(log_mu, "log_mu");
      net_.setInput(log_nu, "log_nu");
      out = net_.forward("scores");
    } catch (const cv::Exception&) {
      SLAM_THROW(InputError) << path << ": not a SuperGlue model (it does not run with inputs "
                             << "keypoints0/1, scores0/1, descriptors0/1, log_mu, log_nu and "
                             << "output scores; see docs/features.md)";
    }
  }
  const bool shaped = out.type() == CV_32F && out.dims == 3 && out.size[0] == 1 &&
                      out.size[1] == m + 1 && out.size[2] == n + 1;
  SLAM_THROW_IF_NOT(InputError, shaped)
      << path << ": not a SuperGlue model (output scores must be 1x" << m + 1 << "x" << n + 1
      << " for " << m << " and " << n << " keypoints)";
  return cv::Mat(m + 1, n + 1, CV_32F, out.ptr<float>()).clone();
}

std::vector<cv::DMatch> SuperGlueMatcher::Match(const FrameFeatures& query,
                                                const cv::Size& query_image,
                                                const FrameFeatures& train,
                                                const cv::Size& train_image) const {
  if (query.empty() || train.empty()) return {};
  return DecodeSuperGlueAssignment(LogAssignment(query, query_image, train, train_image),
                                   options_.match_threshold);
}

}  // namespace duskmap
