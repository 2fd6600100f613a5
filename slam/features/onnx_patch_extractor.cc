#include "slam/features/onnx_patch_extractor.h"

#include <algorithm>
#include <fstream>
#include <iterator>
#include <sstream>

#include "slam/core/check.h"
#include "slam/core/input_file.h"
#include "slam/features/dense_feature_maps.h"
#include "slam/features/embedded_model.h"
#include "slam/features/onnx_declared_input.h"
#include "slam/features/opencv_extractors.h"

namespace duskmap {
namespace {

std::string ShapeOf(const cv::Mat& blob) {
  std::ostringstream out;
  for (int d = 0; d < blob.dims; ++d) out << (d ? "x" : "") << blob.size[d];
  return out.str();
}

// Patches checked when the extractor is built: black and mid-grey.
constexpr int kCheckPatches = 2;

}  // namespace

OnnxPatchExtractor::OnnxPatchExtractor(const OnnxFeatureOptions& options, const SiftOptions& sift,
                                       int max_features, double max_depth_m, FeatureTypeId type)
    : FeatureExtractor(max_features, max_depth_m),
      options_(options),
      type_name_(FeatureTypeName(type)) {
  options_.CheckAs(type);
  SLAM_THROW_IF_NOT(ConfigError, options_.contract == "patch")
      << "features." << type_name_ << ".contract: the patch extractor runs the 'patch' contract, not '"
      << options_.contract << "'";
  sampler_.patch_size_px = options_.patch_size_px;
  sampler_.support_per_size = options_.support_per_size;
  sampler_.oriented = options_.oriented;
  sampler_.Check();
  detector_ = CreateSiftFeature2D(sift, max_features);  // detector "dog", the only one
  SLAM_THROW_IF_NOT(InputError, !options_.model_path.empty() || type == FeatureTypeId::kDuskNet)
      << "features." << type_name_ << ".model_path: no ONNX model given (see docs/features.md)";
  ReadModel();
  // The contract, once, on a small batch of blank patches.
  const int area = options_.patch_size_px * options_.patch_size_px;
  cv::Mat blank(kCheckPatches, area, CV_8U, cv::Scalar(0));
  blank.row(1).setTo(128);
  dims_ = RunBatch(blank).cols;
}

void OnnxPatchExtractor::ReadModel() {
  const std::string& path = options_.model_path;
  std::string file_bytes;  // a model file's bytes, read once
  const char* bytes = nullptr;
  size_t size = 0;
  if (path.empty()) {
    const EmbeddedModel& model = EmbeddedDuskNetModel();
    model_name_ = model.name;
    bytes = model.bytes;
    size = model.size;
  } else {
    model_name_ = path;
    RefuseNonRegularFile(path);  // before opening: a FIFO would block
    std::ifstream in(path, std::ios::binary);
    SLAM_THROW_IF_NOT(InputError, in.good()) << path << ": ONNX model not found";
    file_bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    SLAM_THROW_IF_NOT(InputError, !in.bad()) << path << ": cannot read the ONNX model";
    bytes = file_bytes.data();
    size = file_bytes.size();
  }
  try {
    net_ = cv::dnn::readNetFromONNX(bytes, size);
  } catch (const cv::Exception&) {
    SLAM_THROW(InputError) << model_name_ << ": not a readable ONNX model";
  }
  SLAM_THROW_IF_NOT(InputError, !net_.empty()) << model_name_ << ": empty network";
  CheckDeclaredInput(bytes, size);
  net_.setPreferableBackend(cv::dnn::DNN_BACKEND_OPENCV);
  net_.setPreferableTarget(cv::dnn::DNN_TARGET_CPU);
}

void OnnxPatchExtractor::CheckDeclaredInput(const char* bytes, size_t size) const {
  const auto input = ReadOnnxDeclaredInput(bytes, size);
  if (!input || !input->has_shape) return;  // nothing declared: the check batch decides
  const std::vector<int64_t>& d = input->dims;
  const int64_t p = options_.patch_size_px;
  const auto fixed_or = [](int64_t dim, int64_t want) { return dim < 0 || dim == want; };
  SLAM_THROW_IF_NOT(InputError, d.size() == 4 && fixed_or(d[1], 1) && fixed_or(d[2], p) &&
                                    fixed_or(d[3], p))
      << model_name_ << ": the patch contract needs input Nx1xPxP with P = patch_size_px = " << p
      << "; the model declares its input '" << input->name << "' as " << input->ToString();
}

cv::Mat OnnxPatchExtractor::RunBatch(const cv::Mat& patches) const {
  const int n = patches.rows, p = options_.patch_size_px;
  const double spread = options_.input_std.front(), mean = options_.input_mean.front();
  cv::Mat values;
  patches.convertTo(values, CV_32F, options_.input_scale / spread, -mean / spread);
  const int shape[] = {n, 1, p, p};
  const cv::Mat blob(4, shape, CV_32F, values.ptr<float>());
  const std::string input = std::to_string(n) + "x1x" + std::to_string(p) + "x" + std::to_string(p);
  std::vector<cv::Mat> outputs;
  std::vector<std::string> names;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    try {
      net_.setInput(blob);
      names = net_.getUnconnectedOutLayersNames();
      net_.forward(outputs, names);
    } catch (const cv::Exception&) {
      SLAM_THROW(InputError) << model_name_ << ": the network fails on a " << input
                             << " input (the patch contract: input Nx1xPxP, P = patch_size_px = "
                             << p << ")";
    }
  }
  SLAM_THROW_IF_NOT(InputError, outputs.size() == 1)
      << model_name_ << ": the patch contract needs one output NxD; the model has "
      << outputs.size();
  const cv::Mat& out = outputs.front();
  const int want = options_.descriptor_dims;
  SLAM_THROW_IF_NOT(InputError, out.type() == CV_32F && out.dims == 2 && out.size[0] == n &&
                                    out.size[1] >= 1 && (want == 0 || out.size[1] == want))
      << model_name_ << ": the patch contract needs an output NxD float ("
      << (want > 0 ? "D = " + std::to_string(want) : std::string("any D")) << ") for a " << input
      << " input, got " << ShapeOf(out);
  SLAM_THROW_IF_NOT(InputError, cv::checkRange(out))
      << model_name_ << ": the model's output holds NaN or infinite values";
  SLAM_THROW_IF_NOT(InputError, dims_ == 0 || out.size[1] == dims_)
      << model_name_ << ": the model's descriptors changed from " << dims_ << " to "
      << out.size[1] << " values";
  return out.clone();
}

cv::Mat OnnxPatchExtractor::Describe(const cv::Mat& gray,
                                     const std::vector<cv::KeyPoint>& keypoints) const {
  if (keypoints.empty()) return cv::Mat();
  const cv::Mat patches = PatchSampler(gray, sampler_).Sample(keypoints);
  cv::Mat descriptors(patches.rows, dims_, CV_32F);
  for (int first = 0; first < patches.rows; first += options_.batch_size) {
    const int last = std::min(patches.rows, first + options_.batch_size);
    RunBatch(patches.rowRange(first, last)).copyTo(descriptors.rowRange(first, last));
  }
  NormalizeRows(&descriptors);
  return descriptors;
}

void OnnxPatchExtractor::DetectAndDescribe(const cv::Mat& image,
                                           std::vector<cv::KeyPoint>* keypoints,
                                           cv::Mat* descriptors) const {
  *keypoints = DetectStrongest(*detector_, image, max_features());
  *descriptors = Describe(image, *keypoints);
}

}  // namespace duskmap
