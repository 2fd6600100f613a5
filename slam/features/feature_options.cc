#include "slam/features/feature_options.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <initializer_list>

#include "slam/features/feature_registry.h"

namespace duskmap {

#define FEATURE_OPTION_CHECK(cond, name) \
  SLAM_THROW_IF_NOT(ConfigError, cond) << "features." << name << ": must satisfy " #cond
// A type's option, under its registered name (feature_registry.h).
#define FEATURE_TYPE_OPTION_CHECK(cond, type_id, name) \
  SLAM_THROW_IF_NOT(ConfigError, cond)                 \
      << "features." << FeatureTypeName(type_id) << "." << name << ": must satisfy " #cond

void H5FeatureOptions::Check() const {
  SLAM_THROW_IF_NOT(ConfigError, descriptor_kind == "float" || descriptor_kind == "binary")
      << "features." << FeatureTypeName(FeatureTypeId::kH5) << ".descriptor_kind: '"
      << descriptor_kind
      << "' unknown (float: L2 over float32/float16; binary: Hamming over uint8)";
  SLAM_THROW_IF_NOT(ConfigError,
                    keypoint_origin == "pixel_centre" || keypoint_origin == "pixel_corner")
      << "features." << FeatureTypeName(FeatureTypeId::kH5) << ".keypoint_origin: '"
      << keypoint_origin << "' unknown (pixel_centre: OpenCV and hloc; pixel_corner: COLMAP)";
}

void SurfOptions::Check() const {
  FEATURE_TYPE_OPTION_CHECK(hessian_threshold >= 0.0, FeatureTypeId::kSurf, "hessian_threshold");
  FEATURE_TYPE_OPTION_CHECK(octaves >= 1 && octaves <= 6, FeatureTypeId::kSurf, "octaves");
  FEATURE_TYPE_OPTION_CHECK(octave_layers >= 1 && octave_layers <= 8, FeatureTypeId::kSurf,
                            "octave_layers");
}
void SiftOptions::Check() const {
  FEATURE_TYPE_OPTION_CHECK(octave_layers >= 1, FeatureTypeId::kSift, "octave_layers");
  FEATURE_TYPE_OPTION_CHECK(contrast_threshold >= 0.0, FeatureTypeId::kSift, "contrast_threshold");
  FEATURE_TYPE_OPTION_CHECK(edge_threshold > 0.0, FeatureTypeId::kSift, "edge_threshold");
  FEATURE_TYPE_OPTION_CHECK(sigma > 0.0, FeatureTypeId::kSift, "sigma");
}
void OrbOptions::Check() const {
  FEATURE_TYPE_OPTION_CHECK(scale_factor > 1.0 && scale_factor <= 4.0, FeatureTypeId::kOrb,
                            "scale_factor");
  FEATURE_TYPE_OPTION_CHECK(levels >= 1 && levels <= 16, FeatureTypeId::kOrb, "levels");
  FEATURE_TYPE_OPTION_CHECK(edge_threshold >= 0 && edge_threshold <= 256, FeatureTypeId::kOrb,
                            "edge_threshold");
  FEATURE_TYPE_OPTION_CHECK(patch_size >= 2 && patch_size <= 256, FeatureTypeId::kOrb,
                            "patch_size");
  FEATURE_TYPE_OPTION_CHECK(fast_threshold >= 1 && fast_threshold <= 255, FeatureTypeId::kOrb,
                            "fast_threshold");
}
void BriskOptions::Check() const {
  FEATURE_TYPE_OPTION_CHECK(threshold >= 1 && threshold <= 255, FeatureTypeId::kBrisk, "threshold");
  FEATURE_TYPE_OPTION_CHECK(octaves >= 0 && octaves <= 8, FeatureTypeId::kBrisk, "octaves");
  FEATURE_TYPE_OPTION_CHECK(pattern_scale > 0.0, FeatureTypeId::kBrisk, "pattern_scale");
}
void KazeOptions::Check() const {
  FEATURE_TYPE_OPTION_CHECK(threshold > 0.0, FeatureTypeId::kKaze, "threshold");
  FEATURE_TYPE_OPTION_CHECK(octaves >= 1, FeatureTypeId::kKaze, "octaves");
  FEATURE_TYPE_OPTION_CHECK(octave_layers >= 1, FeatureTypeId::kKaze, "octave_layers");
}
void AkazeOptions::Check() const {
  FEATURE_TYPE_OPTION_CHECK(threshold > 0.0, FeatureTypeId::kAkaze, "threshold");
  FEATURE_TYPE_OPTION_CHECK(octaves >= 1, FeatureTypeId::kAkaze, "octaves");
  FEATURE_TYPE_OPTION_CHECK(octave_layers >= 1, FeatureTypeId::kAkaze, "octave_layers");
}
void GfttOptions::Check() const {
  FEATURE_OPTION_CHECK(quality_level > 0.0 && quality_level < 1.0, "gftt.quality_level");
  FEATURE_OPTION_CHECK(min_distance_px >= 0.0, "gftt.min_distance_px");
  FEATURE_OPTION_CHECK(block_size >= 2, "gftt.block_size");
}
void FastOptions::Check() const { FEATURE_OPTION_CHECK(threshold >= 1, "fast.threshold"); }
void BriefOptions::Check() const {
  FEATURE_TYPE_OPTION_CHECK(bytes == 16 || bytes == 32 || bytes == 64, FeatureTypeId::kBrief,
                            "bytes");
  FEATURE_TYPE_OPTION_CHECK(patch_size_px >= 8 && patch_size_px <= 128, FeatureTypeId::kBrief,
                            "patch_size_px");
  FEATURE_TYPE_OPTION_CHECK(smooth_sigma_px >= 0.0, FeatureTypeId::kBrief, "smooth_sigma_px");
}
void DaisyOptions::Check() const {
  FEATURE_TYPE_OPTION_CHECK(radius_px > 0.0, FeatureTypeId::kDaisy, "radius_px");
  FEATURE_TYPE_OPTION_CHECK(rings >= 1 && rings <= 8, FeatureTypeId::kDaisy, "rings");
  FEATURE_TYPE_OPTION_CHECK(ring_points >= 1 && ring_points <= 32, FeatureTypeId::kDaisy,
                            "ring_points");
  FEATURE_TYPE_OPTION_CHECK(orientations >= 2 && orientations <= 32, FeatureTypeId::kDaisy,
                            "orientations");
}
void FreakOptions::Check() const {
  FEATURE_TYPE_OPTION_CHECK(detector == "gftt" || detector == "fast", FeatureTypeId::kFreak,
                            "detector");
  FEATURE_TYPE_OPTION_CHECK(pattern_scale > 0.0, FeatureTypeId::kFreak, "pattern_scale");
}
void SuperPointOptions::Check() const {
  FEATURE_TYPE_OPTION_CHECK(threshold > 0.0 && threshold < 1.0, FeatureTypeId::kSuperPoint,
                            "threshold");
  FEATURE_TYPE_OPTION_CHECK(nms_radius_px >= 0, FeatureTypeId::kSuperPoint, "nms_radius_px");
  FEATURE_TYPE_OPTION_CHECK(border_px >= 0, FeatureTypeId::kSuperPoint, "border_px");
}

namespace {

void CheckOneOf(const std::string& value, std::initializer_list<const char*> allowed,
                const std::string& key, FeatureTypeId type) {
  std::string known;
  for (const char* a : allowed) {
    if (value == a) return;
    known += (known.empty() ? "" : ", ") + std::string(a);
  }
  SLAM_THROW(ConfigError) << "features." << FeatureTypeName(type) << "." << key
                          << ": '" << value << "' unknown (" << known << ")";
}

}  // namespace

void OnnxFeatureOptions::CheckAs(FeatureTypeId type) const {
  CheckOneOf(contract, {"dense", "sparse", "patch"}, "contract", type);
  CheckOneOf(detector, {"dog"}, "detector", type);
  CheckOneOf(input_color, {"gray", "rgb", "bgr"}, "input_color", type);
  CheckOneOf(score_layout, {"cells", "map"}, "score_layout", type);
  CheckOneOf(score_activation, {"none", "sigmoid"}, "score_activation", type);
  CheckOneOf(descriptors_layout, {"n_by_d", "d_by_n"}, "descriptors_layout", type);
  CheckOneOf(keypoint_origin, {"pixel_centre", "pixel_corner"}, "keypoint_origin", type);
  FEATURE_TYPE_OPTION_CHECK(std::isfinite(input_scale) && input_scale > 0.0, type,
                            "input_scale");
  const size_t channels = input_color == "gray" ? 1 : 3;
  FEATURE_TYPE_OPTION_CHECK(input_mean.size() == 1 || input_mean.size() == channels,
                            type,
                            "input_mean (one value, or one per input channel)");
  FEATURE_TYPE_OPTION_CHECK(input_std.size() == 1 || input_std.size() == channels,
                            type,
                            "input_std (one value, or one per input channel)");
  for (const double m : input_mean)
    FEATURE_TYPE_OPTION_CHECK(std::isfinite(m), type, "input_mean");
  for (const double s : input_std)
    FEATURE_TYPE_OPTION_CHECK(std::isfinite(s) && s > 0.0, type, "input_std");
  FEATURE_TYPE_OPTION_CHECK(input_multiple_px >= 1 && input_multiple_px <= 256,
                            type, "input_multiple_px");
  FEATURE_TYPE_OPTION_CHECK(descriptor_dims >= 0 && descriptor_dims <= 8192, type,
                            "descriptor_dims");
  FEATURE_TYPE_OPTION_CHECK(cell_size_px >= 1 && cell_size_px <= 64, type,
                            "cell_size_px");
  FEATURE_TYPE_OPTION_CHECK(descriptor_stride_px >= 1 && descriptor_stride_px <= 64,
                            type, "descriptor_stride_px");
  FEATURE_TYPE_OPTION_CHECK(nms_radius_px >= 0 && nms_radius_px <= 64, type,
                            "nms_radius_px");
  FEATURE_TYPE_OPTION_CHECK(std::isfinite(threshold), type, "threshold");
  FEATURE_TYPE_OPTION_CHECK(border_px >= 0 && border_px <= 4096, type, "border_px");
  FEATURE_TYPE_OPTION_CHECK(patch_size_px >= 8 && patch_size_px <= 256, type, "patch_size_px");
  FEATURE_TYPE_OPTION_CHECK(std::isfinite(support_per_size) && support_per_size > 0.0, type,
                            "support_per_size");
  FEATURE_TYPE_OPTION_CHECK(batch_size >= 1 && batch_size <= 65536, type, "batch_size");
  SLAM_THROW_IF_NOT(ConfigError, contract != "patch" || input_color == "gray")
      << "features." << FeatureTypeName(type) << ".input_color: the patch contract's input is gray";
  if (contract == "dense") {  // the maps' sizes are the padded input's over their strides
    FEATURE_TYPE_OPTION_CHECK(score_layout != "cells" || input_multiple_px % cell_size_px == 0,
                              type,
                              "input_multiple_px (a multiple of cell_size_px)");
    FEATURE_TYPE_OPTION_CHECK(input_multiple_px % descriptor_stride_px == 0, type,
                              "input_multiple_px (a multiple of descriptor_stride_px)");
  }
}

OnnxFeatureOptions DuskNetFeatureOptions() {
  OnnxFeatureOptions o;
  o.contract = "patch";
  o.descriptor_dims = 128;
  o.detector = "dog";
  o.patch_size_px = 32;
  o.support_per_size = 6.0;
  o.oriented = true;
  return o;
}

void FeatureOptions::Check() const {
  const FeatureType* known = FindFeatureType(type);
  SLAM_THROW_IF_NOT(ConfigError, known != nullptr)
      << "features.type: unknown feature type '" << type << "' (known: " << KnownFeatureTypeNames()
      << "; experiment configs use the paper's column codes instead: " << KnownFeatureColumnCodes()
      << ")";
  // 100,000 features of a 640x480 frame are one every 3 pixels: past any use.
  FEATURE_OPTION_CHECK(max_features >= 1 && max_features <= 100000, "max_features");
  FEATURE_OPTION_CHECK(vocabulary_features >= 1 && vocabulary_features <= max_features,
                       "vocabulary_features");
  FEATURE_OPTION_CHECK(max_depth_m >= 0.0, "max_depth_m");
  surf.Check();
  sift.Check();
  orb.Check();
  brisk.Check();
  kaze.Check();
  akaze.Check();
  gftt.Check();
  fast.Check();
  brief.Check();
  daisy.Check();
  freak.Check();
  superpoint.Check();
  onnx.Check();
  h5.Check();
  dusknet.CheckAs(FeatureTypeId::kDuskNet);
  const std::optional<FeatureFileSpec>& file = known->file;
  SLAM_THROW_IF_NOT(ConfigError, !file || file->required.empty() || !FeatureFilePath(*this).empty())
      << "features." << file->key << ": features of type " << type << " need " << file->required;
}

const std::string& FeatureFilePath(const FeatureOptions& options) {
  static const std::string kNone;
  const FeatureType* type = FindFeatureType(options.type);
  if (type == nullptr) return kNone;
  switch (type->id) {
    case FeatureTypeId::kSuperPoint:
      return options.superpoint.model_path;
    case FeatureTypeId::kOnnx:
      return options.onnx.model_path;
    case FeatureTypeId::kH5:
      return options.h5.path;
    case FeatureTypeId::kDuskNet:
      return options.dusknet.model_path;
    default:
      return kNone;
  }
}

const std::vector<std::string>& BuiltInFeatureTypeNames() {
  static const std::vector<std::string> kNames = [] {
    std::vector<std::string> names;
    for (const FeatureType& type : FeatureTypes()) {
      if (!type.file) names.push_back(type.name);
    }
    return names;
  }();
  return kNames;
}

const std::vector<std::string>& FeatureTypeNames() {
  static const std::vector<std::string> kNames = [] {
    std::vector<std::string> names;
    for (const FeatureType& type : FeatureTypes()) names.push_back(type.name);
    return names;
  }();
  return kNames;
}

std::string FeatureTypeFromName(const std::string& name, const std::string& where) {
  std::string lower = name;
  for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  SLAM_THROW_IF_NOT(ConfigError, FindFeatureType(lower) != nullptr)
      << where << ": unknown feature type '" << name << "' (known: " << KnownFeatureTypeNames()
      << ")";
  return lower;
}

}  // namespace duskmap
