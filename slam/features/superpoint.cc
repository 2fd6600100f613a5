#include "slam/features/superpoint.h"

#include <algorithm>
#include <cmath>
#include <fstream>

#include <opencv2/imgproc.hpp>

#include "slam/core/check.h"

namespace duskmap {
namespace {

constexpr int kCell = 8;

cv::Mat MaxPool(const cv::Mat& m, int radius) {
  cv::Mat out;
  cv::dilate(m, out, cv::getStructuringElement(cv::MORPH_RECT,
                                                cv::Size(2 * radius + 1, 2 * radius + 1)),
             cv::Point(-1, -1), 1, cv::BORDER_CONSTANT, cv::Scalar(-1.0));
  return out;
}

}  // namespace

cv::Mat DecodeSuperPointHeatmap(const cv::Mat& semi) {
  SLAM_CHECK(semi.dims == 4 && semi.size[1] == 65);
  const int hc = semi.size[2], wc = semi.size[3];
  cv::Mat heat(hc * kCell, wc * kCell, CV_32F);
  std::vector<const float*> planes(65);
  for (int k = 0; k < 65; ++k) planes[k] = semi.ptr<float>(0, k);
  float logits[65];
  for (int y = 0; y < hc; ++y) {
    for (int x = 0; x < wc; ++x) {
      const int idx = y * wc + x;
      float max_logit = planes[0][idx];
      for (int k = 0; k < 65; ++k) max_logit = std::max(max_logit, planes[k][idx]);
      double sum = 0.0;
      for (int k = 0; k < 65; ++k) {
        logits[k] = std::exp(planes[k][idx] - max_logit);
        sum += logits[k];
      }
      for (int k = 0; k < 64; ++k) {  // channel k = row (k / 8), column (k % 8) of the cell
        heat.at<float>(y * kCell + k / kCell, x * kCell + k % kCell) =
            static_cast<float>(logits[k] / sum);
      }
    }
  }
  return heat;
}

cv::Mat SuperPointNms(const cv::Mat& scores, int radius_px) {
  if (radius_px <= 0) return scores.clone();
  cv::Mat max_mask = scores == MaxPool(scores, radius_px);  // 255 where local maximum
  for (int pass = 0; pass < 2; ++pass) {
    cv::Mat suppressed = MaxPool(max_mask, radius_px) > 0;
    cv::Mat supp_scores = scores.clone();
    supp_scores.setTo(0.0f, suppressed);
    cv::Mat new_max = supp_scores == MaxPool(supp_scores, radius_px);
    max_mask |= new_max & ~suppressed;
  }
  cv::Mat out = cv::Mat::zeros(scores.size(), CV_32F);
  scores.copyTo(out, max_mask);
  return out;
}

cv::Mat SampleSuperPointDescriptors(const cv::Mat& desc, const std::vector<cv::KeyPoint>& keypoints) {
  SLAM_CHECK(desc.dims == 4);
  const int dims = desc.size[1], hc = desc.size[2], wc = desc.size[3];
  cv::Mat out(static_cast<int>(keypoints.size()), dims, CV_32F);
  for (size_t i = 0; i < keypoints.size(); ++i) {
    // Cell centres sit at 8 * (j + 0.5) - 0.5 pixels.
    const float x = std::clamp((keypoints[i].pt.x + 0.5f) / kCell - 0.5f, 0.0f, wc - 1.0f);
    const float y = std::clamp((keypoints[i].pt.y + 0.5f) / kCell - 0.5f, 0.0f, hc - 1.0f);
    const int x0 = static_cast<int>(x), y0 = static_cast<int>(y);
    const int x1 = std::min(x0 + 1, wc - 1), y1 = std::min(y0 + 1, hc - 1);
    const float ax = x - x0, ay = y - y0;
    float* row = out.ptr<float>(static_cast<int>(i));
    double norm = 0.0;
    for (int c = 0; c < dims; ++c) {
      const float* p = desc.ptr<float>(0, c);
      const float v = (1 - ay) * ((1 - ax) * p[y0 * wc + x0] + ax * p[y0 * wc + x1]) +
                      ay * ((1 - ax) * p[y1 * wc + x0] + ax * p[y1 * wc + x1]);
      row[c] = v;
      norm += static_cast<double>(v) * v;
    }
    if (norm > 0.0) {
      const float inv = static_cast<float>(1.0 / std::sqrt(norm));
      for (int c = 0; c < dims; ++c) row[c] *= inv;
    }
  }
  return out;
}

SuperPointExtractor::SuperPointExtractor(const SuperPointOptions& options, int max_features,
                                         double max_depth_m)
    : FeatureExtractor(max_features, max_depth_m), options_(options) {
  options_.Check();
  SLAM_THROW_IF_NOT(InputError, !options_.model_path.empty())
      << "features.superpoint.model_path: no ONNX model given (see docs/features.md)";
  SLAM_THROW_IF_NOT(InputError, std::ifstream(options_.model_path).good())
      << options_.model_path << ": SuperPoint ONNX model not found";
  try {
    net_ = cv::dnn::readNetFromONNX(options_.model_path);
  } catch (const cv::Exception& e) {
    SLAM_THROW(InputError) << options_.model_path << ": not a readable ONNX model";
  }
  SLAM_THROW_IF_NOT(InputError, !net_.empty()) << options_.model_path << ": empty network";
  // Validate the output shapes once on a small input.
  cv::Mat semi, desc;
  Forward(cv::Mat::zeros(16, 16, CV_32F), &semi, &desc);
}

void SuperPointExtractor::Forward(const cv::Mat& input, cv::Mat* semi, cv::Mat* desc) const {
  std::lock_guard<std::mutex> lock(mutex_);
  std::vector<cv::Mat> outputs;
  try {
    net_.setInput(cv::dnn::blobFromImage(input));
    net_.forward(outputs, net_.getUnconnectedOutLayersNames());
  } catch (const cv::Exception& e) {
    SLAM_THROW(InputError) << options_.model_path << ": network failed to run on a "
                           << input.cols << "x" << input.rows << " image";
  }
  semi->release();
  desc->release();
  for (const cv::Mat& out : outputs) {
    if (out.dims != 4 || out.size[0] != 1 || out.size[2] != input.rows / kCell ||
        out.size[3] != input.cols / kCell) {
      continue;
    }
    if (out.size[1] == 65) *semi = out;
    if (out.size[1] == 256) *desc = out;
  }
  SLAM_THROW_IF_NOT(InputError, !semi->empty() && !desc->empty())
      << options_.model_path
      << ": not a SuperPoint model (needs outputs 1x65xH/8xW/8 and 1x256xH/8xW/8)";
}

void SuperPointExtractor::DetectAndDescribe(const cv::Mat& gray, std::vector<cv::KeyPoint>* keypoints,
                                            cv::Mat* descriptors) const {
  if (gray.cols < kCell || gray.rows < kCell) return;
  cv::Mat input;
  gray.convertTo(input, CV_32F, 1.0 / 255.0);
  const int pad_x = (kCell - gray.cols % kCell) % kCell, pad_y = (kCell - gray.rows % kCell) % kCell;
  cv::copyMakeBorder(input, input, 0, pad_y, 0, pad_x, cv::BORDER_REPLICATE);
  cv::Mat semi, desc;
  Forward(input, &semi, &desc);
  const cv::Mat scores = SuperPointNms(DecodeSuperPointHeatmap(semi), options_.nms_radius_px);
  const int b = options_.border_px;
  for (int y = b; y < gray.rows - b; ++y) {
    const float* row = scores.ptr<float>(y);
    for (int x = b; x < gray.cols - b; ++x) {
      if (row[x] > options_.threshold) {
        keypoints->emplace_back(cv::Point2f(float(x), float(y)), float(kCell), -1.0f, row[x]);
      }
    }
  }
  cv::Mat none;
  KeepStrongest(max_features(), keypoints, &none);
  if (keypoints->empty()) return;
  *descriptors = SampleSuperPointDescriptors(desc, *keypoints);
}

}  // namespace duskmap
