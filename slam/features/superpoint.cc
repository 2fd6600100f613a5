#include "slam/features/superpoint.h"

#include "slam/features/onnx_extractor.h"

namespace duskmap {

OnnxFeatureOptions SuperPointContract(const SuperPointOptions& options) {
  options.Check();
  OnnxFeatureOptions o;
  o.model_path = options.model_path;
  o.contract = "dense";
  o.input_color = "gray";
  o.input_scale = 1.0 / 255.0;
  o.input_mean = {0.0};
  o.input_std = {1.0};
  o.input_multiple_px = 8;
  o.score_layout = "cells";
  o.cell_size_px = 8;
  o.dustbin = true;
  o.descriptor_stride_px = 8;
  o.descriptor_dims = 256;
  o.nms_radius_px = options.nms_radius_px;
  o.threshold = options.threshold;
  o.border_px = options.border_px;
  o.normalize_descriptors = true;
  return o;
}

std::unique_ptr<FeatureExtractor> CreateSuperPointExtractor(const SuperPointOptions& options,
                                                            int max_features, double max_depth_m) {
  return std::make_unique<OnnxFeatureExtractor>(SuperPointContract(options), max_features,
                                                max_depth_m, FeatureTypeId::kSuperPoint, "SuperPoint");
}

}  // namespace duskmap
