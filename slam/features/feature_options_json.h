// JSON codecs of the features module's options (slam/core/json_codec.h): one
// field list per struct gives the reader of configs and the writer of a
// map's stored feature options, so a map records exactly what was read.
//   {"type": "sift", "max_features": 1000, "sift": {"contrast_threshold": 0.02}}
#pragma once

#include <string>
#include <utility>

#include <nlohmann/json.hpp>

#include "slam/core/json_codec.h"
#include "slam/features/binary_distance.h"
#include "slam/features/descriptor_quantization.h"
#include "slam/features/feature_options.h"
#include "slam/features/feature_registry.h"
#include "slam/features/matcher_options.h"

namespace duskmap {

template <>
struct JsonEnumNames<BinaryDistance> {
  static constexpr std::pair<BinaryDistance, const char*> kNames[] = {
      {BinaryDistance::kByteL1, "byte_l1"}, {BinaryDistance::kHamming, "hamming"}};
};

template <>
struct JsonEnumNames<DescriptorStorage> {
  static constexpr std::pair<DescriptorStorage, const char*> kNames[] = {
      {DescriptorStorage::kFloat32, "float32"}, {DescriptorStorage::kUint8, "uint8"}};
};

template <>
struct JsonCodec<SurfOptions> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    f("hessian_threshold", o.hessian_threshold);
    f("octaves", o.octaves);
    f("octave_layers", o.octave_layers);
    f("extended", o.extended);
    f("upright", o.upright);
  }
};

template <>
struct JsonCodec<SiftOptions> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    f("octave_layers", o.octave_layers);
    f("contrast_threshold", o.contrast_threshold);
    f("edge_threshold", o.edge_threshold);
    f("sigma", o.sigma);
    f("root_sift", o.root_sift);
  }
};

template <>
struct JsonCodec<OrbOptions> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    f("scale_factor", o.scale_factor);
    f("levels", o.levels);
    f("edge_threshold", o.edge_threshold);
    f("patch_size", o.patch_size);
    f("fast_threshold", o.fast_threshold);
  }
};

template <>
struct JsonCodec<BriskOptions> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    f("threshold", o.threshold);
    f("octaves", o.octaves);
    f("pattern_scale", o.pattern_scale);
  }
};

template <>
struct JsonCodec<KazeOptions> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    f("extended", o.extended);
    f("upright", o.upright);
    f("threshold", o.threshold);
    f("octaves", o.octaves);
    f("octave_layers", o.octave_layers);
    f("single_pass", o.single_pass);
  }
};

template <>
struct JsonCodec<AkazeOptions> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    f("threshold", o.threshold);
    f("octaves", o.octaves);
    f("octave_layers", o.octave_layers);
  }
};

template <>
struct JsonCodec<GfttOptions> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    f("quality_level", o.quality_level);
    f("min_distance_px", o.min_distance_px);
    f("block_size", o.block_size);
  }
};

template <>
struct JsonCodec<FastOptions> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    f("threshold", o.threshold);
  }
};

template <>
struct JsonCodec<BriefOptions> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    f("bytes", o.bytes);
    f("patch_size_px", o.patch_size_px);
    f("smooth_sigma_px", o.smooth_sigma_px);
    f("pattern_seed", o.pattern_seed);
  }
};

template <>
struct JsonCodec<DaisyOptions> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    f("radius_px", o.radius_px);
    f("rings", o.rings);
    f("ring_points", o.ring_points);
    f("orientations", o.orientations);
    f("normalize", o.normalize);
    f("use_orientation", o.use_orientation);
  }
};

template <>
struct JsonCodec<FreakOptions> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    f("detector", o.detector);
    f("orientation_normalized", o.orientation_normalized);
    f("scale_normalized", o.scale_normalized);
    f("pattern_scale", o.pattern_scale);
  }
};

template <>
struct JsonCodec<SuperPointOptions> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    f("model_path", o.model_path);
    f("threshold", o.threshold);
    f("nms_radius_px", o.nms_radius_px);
    f("border_px", o.border_px);
  }
};

template <>
struct JsonCodec<OnnxFeatureOptions> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    f("model_path", o.model_path);
    f("contract", o.contract);
    f("input_color", o.input_color);
    f("input_scale", o.input_scale);
    f("input_mean", o.input_mean);
    f("input_std", o.input_std);
    f("input_multiple_px", o.input_multiple_px);
    f("scores_output", o.scores_output);
    f("descriptors_output", o.descriptors_output);
    f("keypoints_output", o.keypoints_output);
    f("descriptor_dims", o.descriptor_dims);
    f("score_layout", o.score_layout);
    f("cell_size_px", o.cell_size_px);
    f("dustbin", o.dustbin);
    f("score_activation", o.score_activation);
    f("descriptor_stride_px", o.descriptor_stride_px);
    f("nms_radius_px", o.nms_radius_px);
    f("threshold", o.threshold);
    f("border_px", o.border_px);
    f("normalize_descriptors", o.normalize_descriptors);
    f("descriptors_layout", o.descriptors_layout);
    f("keypoint_origin", o.keypoint_origin);
    f("detector", o.detector);
    f("patch_size_px", o.patch_size_px);
    f("support_per_size", o.support_per_size);
    f("oriented", o.oriented);
    f("batch_size", o.batch_size);
  }
};

template <>
struct JsonCodec<H5FeatureOptions> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    f("path", o.path);
    f("descriptor_kind", o.descriptor_kind);
    f("keypoint_origin", o.keypoint_origin);
  }
};

template <>
struct JsonCodec<FeatureOptions> {
  // Each type's options sit under its registered name (feature_registry.h), the one spelling.
  static const char* TypeKey(FeatureTypeId id) { return FeatureTypeName(id).c_str(); }

  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    f("type", o.type);
    f("max_features", o.max_features);
    f("vocabulary_features", o.vocabulary_features);
    f("max_depth_m", o.max_depth_m);
    f(TypeKey(FeatureTypeId::kSurf), o.surf);
    f(TypeKey(FeatureTypeId::kSift), o.sift);
    f(TypeKey(FeatureTypeId::kOrb), o.orb);
    f(TypeKey(FeatureTypeId::kBrisk), o.brisk);
    f(TypeKey(FeatureTypeId::kKaze), o.kaze);
    f(TypeKey(FeatureTypeId::kAkaze), o.akaze);
    f("gftt", o.gftt);
    f("fast", o.fast);
    f(TypeKey(FeatureTypeId::kBrief), o.brief);
    f(TypeKey(FeatureTypeId::kDaisy), o.daisy);
    f(TypeKey(FeatureTypeId::kFreak), o.freak);
    f(TypeKey(FeatureTypeId::kSuperPoint), o.superpoint);
    f(TypeKey(FeatureTypeId::kOnnx), o.onnx);
    f(TypeKey(FeatureTypeId::kH5), o.h5);
    f(TypeKey(FeatureTypeId::kDuskNet), o.dusknet);
  }
};

template <>
struct JsonCodec<SuperGlueOptions> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    f("model_path", o.model_path);
    f("match_threshold", o.match_threshold);
  }
};

template <>
struct JsonCodec<MatcherOptions> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    f("type", o.type);
    f("superglue", o.superglue);
  }
};

// The feature options a map stored (its metadata's feature_parameters text);
// ConfigError naming `map_path` when the text is damaged.
FeatureOptions FeatureOptionsOfMap(const std::string& feature_parameters_json,
                                   const std::string& map_path);

}  // namespace duskmap
