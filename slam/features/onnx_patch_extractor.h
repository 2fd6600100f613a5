// The `patch` contract of the onnx types (feature_options.h): keypoints from
// a named detector ("dog": exactly the sift type's, FeatureOptions::sift and
// max_features, strongest first), a patch per keypoint from PatchSampler
// (patch_sampler.h: patch_size_px, support_per_size, oriented), and a patch
// descriptor network run through OpenCV's DNN module in batches of
// batch_size: input Nx1xPxP float, value = (pixel * input_scale -
// input_mean) / input_std; output NxD float, L2-normalised here. The model
// is checked against the contract once, when the extractor is built: its
// declared input (onnx_declared_input.h), then a small batch of blank
// patches. The dusknet type is this contract with the model embedded in the
// library (embedded_model.h) unless model_path names a file.
#pragma once

#include <mutex>
#include <string>
#include <vector>

#include <opencv2/dnn.hpp>
#include <opencv2/features2d.hpp>

#include "slam/features/feature_extractor.h"
#include "slam/features/feature_registry.h"
#include "slam/features/patch_sampler.h"

namespace duskmap {

class OnnxPatchExtractor : public FeatureExtractor {
 public:
  // `type`: onnx (model_path required) or dusknet (model_path "": the
  // embedded model). Throws ConfigError for bad options, InputError naming
  // the model when it is missing, unreadable, fails on an Nx1xPxP input, or
  // gives anything but one finite NxD output.
  OnnxPatchExtractor(const OnnxFeatureOptions& options, const SiftOptions& sift, int max_features,
                     double max_depth_m, FeatureTypeId type = FeatureTypeId::kOnnx);
  std::string name() const override { return type_name_; }
  DescriptorKind kind() const override { return DescriptorKind::kFloat; }

  // The descriptors of given keypoints on an 8-bit gray image: one
  // L2-normalised CV_32F row each, in their order (empty for none).
  cv::Mat Describe(const cv::Mat& gray, const std::vector<cv::KeyPoint>& keypoints) const;
  // The model's path, or the embedded model's name ("embedded:dusknet.onnx").
  const std::string& model_name() const { return model_name_; }
  int descriptor_dims() const { return dims_; }

 protected:
  void DetectAndDescribe(const cv::Mat& image, std::vector<cv::KeyPoint>* keypoints,
                         cv::Mat* descriptors) const override;

 private:
  void ReadModel();
  // InputError naming the model when its declared input (when it declares
  // one) is not Nx1xPxP: a fully convolutional model runs on any P, so the
  // check batch alone would not catch one made for another patch size.
  void CheckDeclaredInput(const char* bytes, size_t size) const;
  // Rows of patch_size_px² 8-bit values -> one descriptor row each (not
  // normalised); InputError naming the model when the contract is broken.
  cv::Mat RunBatch(const cv::Mat& patches) const;

  OnnxFeatureOptions options_;
  PatchSamplerOptions sampler_;
  std::string type_name_;
  std::string model_name_;
  cv::Ptr<cv::Feature2D> detector_;
  int dims_ = 0;  // D, from the contract check
  mutable cv::dnn::Net net_;  // forward() is non-const in OpenCV
  mutable std::mutex mutex_;
};

}  // namespace duskmap
