#include "slam/features/onnx_extractor.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include <opencv2/imgproc.hpp>

#include "slam/core/check.h"
#include "slam/core/input_file.h"
#include "slam/features/dense_feature_maps.h"

namespace duskmap {
namespace {

std::string ShapeOf(const cv::Mat& blob) {
  std::ostringstream out;
  for (int d = 0; d < blob.dims; ++d) out << (d ? "x" : "") << blob.size[d];
  return out.str();
}

bool IsMap(const cv::Mat& blob, int channels, int rows, int cols) {
  return blob.dims == 4 && blob.type() == CV_32F && blob.size[0] == 1 &&
         (channels <= 0 || blob.size[1] == channels) && blob.size[2] == rows &&
         blob.size[3] == cols;
}

// "1x65x(H/8)x(W/8)"-style shape of a map with `channels` (0: "D") at 1/stride.
std::string MapShape(int channels, int stride) {
  const std::string c = channels > 0 ? std::to_string(channels) : "D";
  if (stride == 1) return "1x" + c + "xHxW";
  const std::string s = std::to_string(stride);
  return "1x" + c + "x(H/" + s + ")x(W/" + s + ")";
}

// The layer type named in OpenCV's "Can't create layer ... of type "X"" error.
std::string MissingLayerType(const std::string& message) {
  const std::string marker = "of type \"";
  const size_t at = message.find(marker);
  if (at == std::string::npos) return "";
  const size_t begin = at + marker.size();
  const size_t end = message.find('"', begin);
  return end == std::string::npos ? "" : message.substr(begin, end - begin);
}

// The index of the output named `name`; -1 when there is none.
int OutputIndex(const std::vector<std::string>& names, const std::string& name) {
  for (size_t i = 0; i < names.size(); ++i) {
    if (names[i] == name) return static_cast<int>(i);
  }
  return -1;
}

}  // namespace

OnnxFeatureExtractor::OnnxFeatureExtractor(const OnnxFeatureOptions& options, int max_features,
                                           double max_depth_m, FeatureTypeId type,
                                           std::string model_label)
    : FeatureExtractor(max_features, max_depth_m),
      options_(options),
      type_name_(FeatureTypeName(type)),
      model_label_(std::move(model_label)) {
  options_.Check();
  const std::string& path = options_.model_path;
  SLAM_THROW_IF_NOT(InputError, !path.empty())
      << "features." << type_name_ << ".model_path: no ONNX model given (see docs/features.md)";
  RefuseNonRegularFile(path);  // before opening: a FIFO would block
  SLAM_THROW_IF_NOT(InputError, std::ifstream(path).good())
      << path << ": " << (model_label_.empty() ? "" : model_label_ + " ")
      << "ONNX model not found";
  try {
    net_ = cv::dnn::readNetFromONNX(path);
  } catch (const cv::Exception& e) {
    const std::string layer = MissingLayerType(e.what());
    if (!layer.empty()) {
      SLAM_THROW(InputError) << path << ": not a readable ONNX model: OpenCV's DNN module has no "
                             << layer << " layer"
                             << (layer == "TopK"
                                     ? " (export the model's score and descriptor maps and "
                                       "use the dense contract)"
                                     : "");
    }
    SLAM_THROW(InputError) << path << ": not a readable ONNX model";
  }
  SLAM_THROW_IF_NOT(InputError, !net_.empty()) << path << ": empty network";
  // Check the contract once, on a small blank image.
  const int side = ((std::max(16, 2 * options_.input_multiple_px) + options_.input_multiple_px - 1) /
                    options_.input_multiple_px) * options_.input_multiple_px;
  const cv::Mat blank(side, side, DetectsOnColor() ? CV_8UC3 : CV_8UC1, cv::Scalar::all(0));
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
  DetectAndDescribe(blank, &keypoints, &descriptors);
}

cv::Mat OnnxFeatureExtractor::InputBlob(const cv::Mat& image) const {
  const OnnxFeatureOptions& o = options_;
  auto mean = [&](size_t c) { return o.input_mean[std::min(c, o.input_mean.size() - 1)]; };
  auto spread = [&](size_t c) { return o.input_std[std::min(c, o.input_std.size() - 1)]; };
  cv::Mat input;
  if (image.channels() == 1) {
    image.convertTo(input, CV_32F, o.input_scale / spread(0), -mean(0) / spread(0));
  } else {
    cv::Mat ordered;
    if (o.input_color == "rgb") {
      cv::cvtColor(image, ordered, cv::COLOR_BGR2RGB);
    } else {
      ordered = image;
    }
    std::vector<cv::Mat> planes;
    cv::split(ordered, planes);
    for (size_t c = 0; c < planes.size(); ++c) {
      planes[c].convertTo(planes[c], CV_32F, o.input_scale / spread(c), -mean(c) / spread(c));
    }
    cv::merge(planes, input);
  }
  const int m = o.input_multiple_px;
  const int pad_x = (m - image.cols % m) % m, pad_y = (m - image.rows % m) % m;
  cv::copyMakeBorder(input, input, 0, pad_y, 0, pad_x, cv::BORDER_REPLICATE);
  return cv::dnn::blobFromImage(input);
}

OnnxFeatureExtractor::Outputs OnnxFeatureExtractor::Forward(const cv::Mat& blob) const {
  std::lock_guard<std::mutex> lock(mutex_);
  Outputs outputs;
  try {
    net_.setInput(blob);
    outputs.names = net_.getUnconnectedOutLayersNames();
    net_.forward(outputs.blobs, outputs.names);
  } catch (const cv::Exception& e) {
    SLAM_THROW(InputError) << options_.model_path << ": network failed to run on a "
                           << blob.size[3] << "x" << blob.size[2] << "x" << blob.size[1]
                           << " input";
  }
  SLAM_CHECK(outputs.blobs.size() == outputs.names.size());
  return outputs;
}

void OnnxFeatureExtractor::ContractError(const Outputs& outputs, const std::string& problem) const {
  std::ostringstream listed;
  for (size_t i = 0; i < outputs.names.size(); ++i) {
    listed << (i ? ", " : "") << outputs.names[i] << " " << ShapeOf(outputs.blobs[i]);
  }
  std::ostringstream message;
  message << options_.model_path << ": ";
  if (model_label_.empty()) {
    message << "the outputs do not match the declared " << options_.contract << " contract";
  } else {
    message << "not a " << model_label_ << " model";
  }
  message << ": " << problem << " (the model's outputs: " << listed.str() << ")";
  throw InputError(message.str());
}

void OnnxFeatureExtractor::PickDenseOutputs(const Outputs& outputs, int padded_rows,
                                            int padded_cols, cv::Mat* scores,
                                            cv::Mat* descriptors) const {
  const OnnxFeatureOptions& o = options_;
  const bool cells = o.score_layout == "cells";
  const int score_stride = cells ? o.cell_size_px : 1;
  const int score_channels = cells ? o.cell_size_px * o.cell_size_px + (o.dustbin ? 1 : 0) : 1;
  const int score_rows = padded_rows / score_stride, score_cols = padded_cols / score_stride;
  const int ds = o.descriptor_stride_px;
  const int desc_rows = padded_rows / ds, desc_cols = padded_cols / ds;
  const std::string needs = "needs a score output " + MapShape(score_channels, score_stride) +
                            " and a descriptor output " + MapShape(o.descriptor_dims, ds);
  int score_index = -1, desc_index = -1;
  for (size_t i = 0; i < outputs.names.size(); ++i) {
    const cv::Mat& blob = outputs.blobs[i];
    const std::string& name = outputs.names[i];
    const bool score_named = !o.scores_output.empty() && name == o.scores_output;
    const bool desc_named = !o.descriptors_output.empty() && name == o.descriptors_output;
    if (score_named || (o.scores_output.empty() && IsMap(blob, score_channels, score_rows, score_cols) &&
                        !desc_named)) {
      if (score_named && !IsMap(blob, score_channels, score_rows, score_cols)) {
        ContractError(outputs, "the score output " + name + " is " + ShapeOf(blob) + "; " + needs);
      }
      if (score_index >= 0) {
        ContractError(outputs, "several outputs fit the score map (name it: scores_output)");
      }
      score_index = static_cast<int>(i);
    }
  }
  const std::string input = " for a " + std::to_string(padded_cols) + "x" +
                            std::to_string(padded_rows) + " input; ";
  if (score_index < 0) {
    ContractError(outputs, needs + input +
                               (o.scores_output.empty() ? "no score output of that shape"
                                                        : "no output named " + o.scores_output));
  }
  for (size_t i = 0; i < outputs.names.size(); ++i) {
    const cv::Mat& blob = outputs.blobs[i];
    const std::string& name = outputs.names[i];
    const bool desc_named = !o.descriptors_output.empty() && name == o.descriptors_output;
    if (static_cast<int>(i) == score_index) continue;
    if (desc_named || (o.descriptors_output.empty() &&
                       IsMap(blob, o.descriptor_dims, desc_rows, desc_cols))) {
      if (desc_named && !IsMap(blob, o.descriptor_dims, desc_rows, desc_cols)) {
        ContractError(outputs,
                      "the descriptor output " + name + " is " + ShapeOf(blob) + "; " + needs);
      }
      if (desc_index >= 0) {
        ContractError(outputs,
                      "several outputs fit the descriptor map (name it: descriptors_output, or "
                      "give descriptor_dims)");
      }
      desc_index = static_cast<int>(i);
    }
  }
  if (desc_index < 0) {
    ContractError(outputs, needs + input +
                               (o.descriptors_output.empty()
                                    ? "no descriptor output of that shape"
                                    : "no output named " + o.descriptors_output));
  }
  // Checked here, where the model is known: a NaN or infinite score map gave 0
  // features (NaN) or every pixel as one (+inf), and a NaN descriptor map
  // failed later without naming the model.
  for (const int index : {score_index, desc_index}) {
    SLAM_THROW_IF_NOT(InputError, cv::checkRange(outputs.blobs[index]))
        << o.model_path << ": the model's " << (index == score_index ? "score" : "descriptor")
        << " output " << outputs.names[index] << " holds NaN or infinite values";
  }
  *scores = outputs.blobs[score_index];
  *descriptors = outputs.blobs[desc_index];
}

void OnnxFeatureExtractor::DecodeDense(const Outputs& outputs, int rows, int cols,
                                       int padded_rows, int padded_cols,
                                       std::vector<cv::KeyPoint>* keypoints,
                                       cv::Mat* descriptors) const {
  const OnnxFeatureOptions& o = options_;
  cv::Mat score_blob, descriptor_blob;
  PickDenseOutputs(outputs, padded_rows, padded_cols, &score_blob, &descriptor_blob);
  const bool cells = o.score_layout == "cells";
  const cv::Mat heat = cells ? DecodeCellScores(score_blob, o.cell_size_px, o.dustbin)
                             : ScoreMapPlane(score_blob, o.score_activation == "sigmoid");
  const cv::Mat scores = MaxPoolNms(heat, o.nms_radius_px);
  const float size = static_cast<float>(cells ? o.cell_size_px : 2 * o.nms_radius_px + 1);
  const int b = o.border_px;
  for (int y = b; y < rows - b; ++y) {
    const float* row = scores.ptr<float>(y);
    for (int x = b; x < cols - b; ++x) {
      if (row[x] > o.threshold) {
        keypoints->emplace_back(cv::Point2f(float(x), float(y)), size, -1.0f, row[x]);
      }
    }
  }
  cv::Mat none;
  KeepStrongest(max_features(), keypoints, &none);
  if (keypoints->empty()) return;
  *descriptors = SampleDescriptorMap(descriptor_blob, *keypoints, o.descriptor_stride_px,
                                     o.normalize_descriptors);
}

void OnnxFeatureExtractor::DecodeSparse(const Outputs& outputs, int rows, int cols,
                                        int padded_rows, int padded_cols,
                                        std::vector<cv::KeyPoint>* keypoints,
                                        cv::Mat* descriptors) const {
  const OnnxFeatureOptions& o = options_;
  const std::string kp_name = o.keypoints_output.empty() ? "keypoints" : o.keypoints_output;
  const std::string desc_name = o.descriptors_output.empty() ? "descriptors" : o.descriptors_output;
  const std::string score_name = o.scores_output.empty() ? "scores" : o.scores_output;
  const int kp_index = OutputIndex(outputs.names, kp_name);
  const int desc_index = OutputIndex(outputs.names, desc_name);
  const int score_index = OutputIndex(outputs.names, score_name);
  if (kp_index < 0) ContractError(outputs, "no output named " + kp_name);
  if (desc_index < 0) ContractError(outputs, "no output named " + desc_name);
  if (score_index < 0 && !o.scores_output.empty()) {
    ContractError(outputs, "no output named " + score_name);
  }
  // Keypoints: 1xNx2 or Nx2.
  const cv::Mat& kp = outputs.blobs[kp_index];
  const bool kp_ok = kp.type() == CV_32F && ((kp.dims == 3 && kp.size[0] == 1 && kp.size[2] == 2) ||
                                             (kp.dims == 2 && kp.size[1] == 2));
  if (!kp_ok) ContractError(outputs, kp_name + " must be 1xNx2 or Nx2, got " + ShapeOf(kp));
  const int n = kp.dims == 3 ? kp.size[1] : kp.size[0];
  // Descriptors: 1xNxD / NxD, or 1xDxN / DxN.
  const cv::Mat& desc = outputs.blobs[desc_index];
  const bool by_rows = o.descriptors_layout == "n_by_d";
  const int outer = desc.dims == 3 ? 1 : 0;
  const bool desc_shape = desc.type() == CV_32F && (desc.dims == 2 || (desc.dims == 3 && desc.size[0] == 1));
  const int desc_n = desc_shape ? desc.size[outer + (by_rows ? 0 : 1)] : -1;
  const int dims = desc_shape ? desc.size[outer + (by_rows ? 1 : 0)] : -1;
  const std::string layout = by_rows ? "1xNxD or NxD" : "1xDxN or DxN";
  if (!desc_shape || desc_n != n || dims < 1 || (o.descriptor_dims > 0 && dims != o.descriptor_dims)) {
    ContractError(outputs, desc_name + " must be " + layout + " with N = " + std::to_string(n) +
                               (o.descriptor_dims > 0 ? " and D = " + std::to_string(o.descriptor_dims)
                                                      : std::string()) +
                               ", got " + ShapeOf(desc));
  }
  const float* scores = nullptr;
  if (score_index >= 0) {
    const cv::Mat& s = outputs.blobs[score_index];
    if (s.type() != CV_32F || s.total() != static_cast<size_t>(n) || !s.isContinuous()) {
      ContractError(outputs, score_name + " must hold N = " + std::to_string(n) +
                                 " scores, got " + ShapeOf(s));
    }
    scores = s.ptr<float>();
  }
  const cv::Mat desc_rows = cv::Mat(by_rows ? n : dims, by_rows ? dims : n, CV_32F,
                                    const_cast<float*>(desc.ptr<float>()));
  const cv::Mat rows_by_keypoint = by_rows ? desc_rows : desc_rows.t();
  SLAM_THROW_IF_NOT(InputError, cv::checkRange(rows_by_keypoint))
      << o.model_path << ": the model's " << desc_name << " hold NaN or infinite values";
  const float* xy = kp.ptr<float>();
  const float shift = o.keypoint_origin == "pixel_corner" ? -0.5f : 0.0f;
  const int b = o.border_px;
  std::vector<int> kept;
  for (int i = 0; i < n; ++i) {
    const float x = xy[2 * i] + shift, y = xy[2 * i + 1] + shift;
    const float score = scores ? scores[i] : 1.0f;
    SLAM_THROW_IF_NOT(InputError, std::isfinite(x) && std::isfinite(y) && std::isfinite(score))
        << o.model_path << ": keypoint " << i << " of the model's output is not finite (" << x
        << ", " << y << ", score " << score << ")";
    SLAM_THROW_IF_NOT(InputError, x >= -0.5f && y >= -0.5f && x < padded_cols - 0.5f &&
                                      y < padded_rows - 0.5f)
        << o.model_path << ": keypoint " << i << " at (" << x << ", " << y
        << ") lies outside the model's " << padded_cols << "x" << padded_rows << " input";
    // Keypoints in the padding, or within border_px of the image's border, are dropped.
    if (x < b || y < b || x > cols - 1 - b || y > rows - 1 - b) continue;
    if (scores && !(score > o.threshold)) continue;
    kept.push_back(i);
    keypoints->emplace_back(cv::Point2f(x, y), static_cast<float>(o.cell_size_px), -1.0f, score);
  }
  if (kept.empty()) return;
  descriptors->create(static_cast<int>(kept.size()), dims, CV_32F);
  for (size_t k = 0; k < kept.size(); ++k) {
    rows_by_keypoint.row(kept[k]).copyTo(descriptors->row(static_cast<int>(k)));
  }
  if (o.normalize_descriptors) NormalizeRows(descriptors);
}

void OnnxFeatureExtractor::DetectAndDescribe(const cv::Mat& image,
                                             std::vector<cv::KeyPoint>* keypoints,
                                             cv::Mat* descriptors) const {
  const int m = options_.input_multiple_px;
  if (image.cols < m || image.rows < m) return;
  const cv::Mat blob = InputBlob(image);
  const int padded_rows = blob.size[2], padded_cols = blob.size[3];
  const Outputs outputs = Forward(blob);
  if (options_.contract == "dense") {
    DecodeDense(outputs, image.rows, image.cols, padded_rows, padded_cols, keypoints, descriptors);
  } else {
    DecodeSparse(outputs, image.rows, image.cols, padded_rows, padded_cols, keypoints, descriptors);
  }
}

}  // namespace duskmap
