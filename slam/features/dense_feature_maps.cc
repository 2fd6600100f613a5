#include "slam/features/dense_feature_maps.h"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

#include "slam/core/check.h"

namespace duskmap {
namespace {

cv::Mat MaxPool(const cv::Mat& m, int radius) {
  cv::Mat out;
  cv::dilate(m, out, cv::getStructuringElement(cv::MORPH_RECT,
                                                cv::Size(2 * radius + 1, 2 * radius + 1)),
             cv::Point(-1, -1), 1, cv::BORDER_CONSTANT, cv::Scalar(-1.0));
  return out;
}

void NormalizeRow(float* row, int dims) {
  double norm = 0.0;
  for (int c = 0; c < dims; ++c) norm += static_cast<double>(row[c]) * row[c];
  if (norm > 0.0) {
    const float inv = static_cast<float>(1.0 / std::sqrt(norm));
    for (int c = 0; c < dims; ++c) row[c] *= inv;
  }
}

}  // namespace

cv::Mat DecodeCellScores(const cv::Mat& logits, int cell_size_px, bool dustbin) {
  const int cell = cell_size_px;
  const int keypoint_channels = cell * cell;
  const int channels = keypoint_channels + (dustbin ? 1 : 0);
  SLAM_CHECK(logits.dims == 4 && logits.type() == CV_32F && logits.size[1] == channels);
  const int hc = logits.size[2], wc = logits.size[3];
  cv::Mat heat(hc * cell, wc * cell, CV_32F);
  std::vector<const float*> planes(channels);
  for (int k = 0; k < channels; ++k) planes[k] = logits.ptr<float>(0, k);
  std::vector<float> weights(channels);
  for (int y = 0; y < hc; ++y) {
    for (int x = 0; x < wc; ++x) {
      const int idx = y * wc + x;
      float max_logit = planes[0][idx];
      for (int k = 0; k < channels; ++k) max_logit = std::max(max_logit, planes[k][idx]);
      double sum = 0.0;
      for (int k = 0; k < channels; ++k) {
        weights[k] = std::exp(planes[k][idx] - max_logit);
        sum += weights[k];
      }
      for (int k = 0; k < keypoint_channels; ++k) {
        heat.at<float>(y * cell + k / cell, x * cell + k % cell) =
            static_cast<float>(weights[k] / sum);
      }
    }
  }
  return heat;
}

cv::Mat ScoreMapPlane(const cv::Mat& map, bool sigmoid) {
  SLAM_CHECK(map.dims == 4 && map.type() == CV_32F && map.size[1] == 1);
  cv::Mat plane(map.size[2], map.size[3], CV_32F, const_cast<float*>(map.ptr<float>(0, 0)));
  plane = plane.clone();
  if (sigmoid) {
    for (int y = 0; y < plane.rows; ++y) {
      float* row = plane.ptr<float>(y);
      for (int x = 0; x < plane.cols; ++x) row[x] = 1.0f / (1.0f + std::exp(-row[x]));
    }
  }
  return plane;
}

cv::Mat MaxPoolNms(const cv::Mat& scores, int radius_px) {
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

cv::Mat SampleDescriptorMap(const cv::Mat& map, const std::vector<cv::KeyPoint>& keypoints,
                            int stride_px, bool normalize) {
  SLAM_CHECK(map.dims == 4 && map.type() == CV_32F && stride_px >= 1);
  const int dims = map.size[1], hc = map.size[2], wc = map.size[3];
  const float stride = static_cast<float>(stride_px);
  cv::Mat out(static_cast<int>(keypoints.size()), dims, CV_32F);
  for (size_t i = 0; i < keypoints.size(); ++i) {
    const float x = std::clamp((keypoints[i].pt.x + 0.5f) / stride - 0.5f, 0.0f, wc - 1.0f);
    const float y = std::clamp((keypoints[i].pt.y + 0.5f) / stride - 0.5f, 0.0f, hc - 1.0f);
    const int x0 = static_cast<int>(x), y0 = static_cast<int>(y);
    const int x1 = std::min(x0 + 1, wc - 1), y1 = std::min(y0 + 1, hc - 1);
    const float ax = x - x0, ay = y - y0;
    float* row = out.ptr<float>(static_cast<int>(i));
    for (int c = 0; c < dims; ++c) {
      const float* p = map.ptr<float>(0, c);
      row[c] = (1 - ay) * ((1 - ax) * p[y0 * wc + x0] + ax * p[y0 * wc + x1]) +
               ay * ((1 - ax) * p[y1 * wc + x0] + ax * p[y1 * wc + x1]);
    }
    if (normalize) NormalizeRow(row, dims);
  }
  return out;
}

void NormalizeRows(cv::Mat* rows) {
  SLAM_CHECK(rows->type() == CV_32F && rows->isContinuous());
  for (int r = 0; r < rows->rows; ++r) NormalizeRow(rows->ptr<float>(r), rows->cols);
}

}  // namespace duskmap
