// SuperGlue (Sarlin, DeTone, Malisiewicz, Rabinovich, CVPR 2020) matching of
// SuperPoint features, run through OpenCV's DNN module from an ONNX file.
//
// Graph contract (docs/features.md; scripts/make_test_superglue_onnx.py
// writes a random-weight model with it): inputs keypoints0 1xMx2 and
// keypoints1 1xNx2 (pixels normalised as the reference does, see
// NormalizeSuperGlueKeypoints), scores0 1xM and scores1 1xN (detection
// scores), descriptors0 1x256xM and descriptors1 1x256xN, log_mu 1x(M+1)x1
// and log_nu 1x(N+1)x1 (the Sinkhorn log marginals times M + N, see
// SuperGlueLogMarginals); output "scores" 1x(M+1)x(N+1), the log assignment
// after the optimal-transport layer, dustbin row and column last. The
// marginals are inputs because OpenCV 4.6 cannot evaluate shape-dependent
// operators on run-time sizes.
//
// Decoding follows the reference: each row's and each column's best entry
// among the real (non-dustbin) columns and rows, kept when the two agree
// (mutual) and exp(score) > match_threshold (PyMatcher/Threshold = 0.2).
#pragma once

#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <opencv2/dnn.hpp>

#include "slam/features/feature_matcher.h"

namespace duskmap {

struct SuperGlueOptions {
  std::string model_path;        // ONNX file (contract above); required
  double match_threshold = 0.2;  // PyMatcher/Threshold: minimum exp(log assignment)
  void Check() const;
};

// Mutual best entries of the inner MxN block of a (M+1)x(N+1) CV_32F log
// assignment with exp(score) > match_threshold. queryIdx = row, trainIdx =
// column, distance = 1 - exp(score) (lower is better); sorted by row.
// Ties go to the lowest index; non-finite entries never win.
std::vector<cv::DMatch> DecodeSuperGlueAssignment(const cv::Mat& log_assignment,
                                                  double match_threshold);

// 1xMx2 CV_32F blob of (p - size / 2) / (0.7 * max(width, height)).
cv::Mat NormalizeSuperGlueKeypoints(const std::vector<cv::KeyPoint>& keypoints,
                                    const cv::Size& image);

// log_mu (1x(M+1)x1) = [0 .. 0, log N] and log_nu (1x(N+1)x1) = [0 .. 0,
// log M]: the reference's marginals [1/(M+N) .. , N/(M+N)] scaled by M + N,
// so that the Sinkhorn output is already the reference's Z - norm.
void SuperGlueLogMarginals(int m, int n, cv::Mat* log_mu, cv::Mat* log_nu);

class SuperGlueMatcher : public FeatureMatcher {
 public:
  // Loads options.model_path and runs it once on a small pair; throws
  // InputError when the file is missing, unreadable or not SuperGlue-shaped.
  explicit SuperGlueMatcher(const SuperGlueOptions& options);
  std::string name() const override { return "superglue"; }

  // Both sides need 256-D CV_32F descriptors (SuperPoint), one row per
  // keypoint, and a non-empty image size; otherwise InputError. Keypoint
  // responses are the detection scores. No keypoints on a side: no matches.
  std::vector<cv::DMatch> Match(const FrameFeatures& query, const cv::Size& query_image,
                                const FrameFeatures& train,
                                const cv::Size& train_image) const override;

  // The network's (M+1)x(N+1) log assignment (query rows, train columns).
  cv::Mat LogAssignment(const FrameFeatures& query, const cv::Size& query_image,
                        const FrameFeatures& train, const cv::Size& train_image) const;

  const SuperGlueOptions& options() const { return options_; }

 private:
  SuperGlueOptions options_;
  mutable cv::dnn::Net net_;  // forward() is non-const in OpenCV
  mutable std::mutex mutex_;
};

}  // namespace duskmap
