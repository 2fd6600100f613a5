// Any ONNX local-feature model, run through OpenCV's DNN module, with the
// contract its OnnxFeatureOptions declare (feature_options.h): the input's
// colour, scale, mean, spread and size multiple, and dense (score map +
// descriptor map) or sparse (keypoints, descriptors, scores) outputs. The
// model is checked against its contract once, on a small blank image, when
// the extractor is built. SuperPoint is one configuration (superpoint.h).
// Keypoint sizes, which nothing in duskmap reads, are cell_size_px (cells
// layout, sparse contract) or 2 nms_radius_px + 1 (map layout).
#pragma once

#include <mutex>
#include <string>
#include <vector>

#include <opencv2/dnn.hpp>

#include "slam/features/feature_extractor.h"
#include "slam/features/feature_registry.h"

namespace duskmap {

class OnnxFeatureExtractor : public FeatureExtractor {
 public:
  // `type` is the feature type (onnx, superpoint); `model_label`
  // names the model kind in contract errors ("SuperPoint": "not a SuperPoint
  // model"). Throws InputError naming the file when the model is missing,
  // unreadable, fails to run, or its outputs do not match the contract.
  OnnxFeatureExtractor(const OnnxFeatureOptions& options, int max_features, double max_depth_m,
                       FeatureTypeId type = FeatureTypeId::kOnnx, std::string model_label = "");
  std::string name() const override { return type_name_; }
  DescriptorKind kind() const override { return DescriptorKind::kFloat; }
  bool DetectsOnColor() const override { return options_.input_color != "gray"; }

 protected:
  void DetectAndDescribe(const cv::Mat& image, std::vector<cv::KeyPoint>* keypoints,
                         cv::Mat* descriptors) const override;

 private:
  // The network's outputs, by name, for one padded input blob.
  struct Outputs {
    std::vector<std::string> names;
    std::vector<cv::Mat> blobs;
  };
  // The 1xCxHxW input blob of an 8-bit image padded to input_multiple_px.
  cv::Mat InputBlob(const cv::Mat& image) const;
  Outputs Forward(const cv::Mat& blob) const;
  // Dense contract: the score and descriptor blobs of a padded_rows x
  // padded_cols input (by name, or found by shape); InputError otherwise, or
  // when either holds NaN or infinity.
  void PickDenseOutputs(const Outputs& outputs, int padded_rows, int padded_cols, cv::Mat* scores,
                        cv::Mat* descriptors) const;
  void DecodeDense(const Outputs& outputs, int rows, int cols, int padded_rows, int padded_cols,
                   std::vector<cv::KeyPoint>* keypoints, cv::Mat* descriptors) const;
  void DecodeSparse(const Outputs& outputs, int rows, int cols, int padded_rows, int padded_cols,
                    std::vector<cv::KeyPoint>* keypoints, cv::Mat* descriptors) const;
  // "<model>: not a <label> model (<contract>): <problem>; outputs: ...".
  [[noreturn]] void ContractError(const Outputs& outputs, const std::string& problem) const;

  OnnxFeatureOptions options_;
  std::string type_name_;
  std::string model_label_;
  mutable cv::dnn::Net net_;  // forward() is non-const in OpenCV
  mutable std::mutex mutex_;
};

}  // namespace duskmap
