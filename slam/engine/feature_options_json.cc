#include "slam/engine/feature_options_json.h"

#include "slam/core/check.h"
#include "slam/core/json_fields.h"

namespace duskmap {

nlohmann::json FeatureOptionsToJson(const FeatureOptions& o) {
  return {
      {"type", o.type},
      {"max_features", o.max_features},
      {"vocabulary_features", o.vocabulary_features},
      {"max_depth_m", o.max_depth_m},
      {"surf",
       {{"hessian_threshold", o.surf.hessian_threshold}, {"octaves", o.surf.octaves},
        {"octave_layers", o.surf.octave_layers}, {"extended", o.surf.extended},
        {"upright", o.surf.upright}}},
      {"sift",
       {{"octave_layers", o.sift.octave_layers},
        {"contrast_threshold", o.sift.contrast_threshold},
        {"edge_threshold", o.sift.edge_threshold}, {"sigma", o.sift.sigma},
        {"root_sift", o.sift.root_sift}}},
      {"orb",
       {{"scale_factor", o.orb.scale_factor}, {"levels", o.orb.levels},
        {"edge_threshold", o.orb.edge_threshold}, {"patch_size", o.orb.patch_size},
        {"fast_threshold", o.orb.fast_threshold}}},
      {"brisk",
       {{"threshold", o.brisk.threshold}, {"octaves", o.brisk.octaves},
        {"pattern_scale", o.brisk.pattern_scale}}},
      {"kaze",
       {{"extended", o.kaze.extended}, {"upright", o.kaze.upright},
        {"threshold", o.kaze.threshold}, {"octaves", o.kaze.octaves},
        {"octave_layers", o.kaze.octave_layers}}},
      {"akaze",
       {{"threshold", o.akaze.threshold}, {"octaves", o.akaze.octaves},
        {"octave_layers", o.akaze.octave_layers}}},
      {"gftt",
       {{"quality_level", o.gftt.quality_level}, {"min_distance_px", o.gftt.min_distance_px},
        {"block_size", o.gftt.block_size}}},
      {"fast", {{"threshold", o.fast.threshold}}},
      {"brief",
       {{"bytes", o.brief.bytes}, {"patch_size_px", o.brief.patch_size_px},
        {"smooth_sigma_px", o.brief.smooth_sigma_px}, {"pattern_seed", o.brief.pattern_seed}}},
      {"daisy",
       {{"radius_px", o.daisy.radius_px}, {"rings", o.daisy.rings},
        {"ring_points", o.daisy.ring_points}, {"orientations", o.daisy.orientations},
        {"normalize", o.daisy.normalize}, {"use_orientation", o.daisy.use_orientation}}},
      {"freak",
       {{"detector", o.freak.detector},
        {"orientation_normalized", o.freak.orientation_normalized},
        {"scale_normalized", o.freak.scale_normalized},
        {"pattern_scale", o.freak.pattern_scale}}},
      {"superpoint",
       {{"model_path", o.superpoint.model_path}, {"threshold", o.superpoint.threshold},
        {"nms_radius_px", o.superpoint.nms_radius_px},
        {"border_px", o.superpoint.border_px}}},
      {"onnx",
       {{"model_path", o.onnx.model_path}, {"contract", o.onnx.contract},
        {"input_color", o.onnx.input_color}, {"input_scale", o.onnx.input_scale},
        {"input_mean", o.onnx.input_mean}, {"input_std", o.onnx.input_std},
        {"input_multiple_px", o.onnx.input_multiple_px},
        {"scores_output", o.onnx.scores_output},
        {"descriptors_output", o.onnx.descriptors_output},
        {"keypoints_output", o.onnx.keypoints_output},
        {"descriptor_dims", o.onnx.descriptor_dims}, {"score_layout", o.onnx.score_layout},
        {"cell_size_px", o.onnx.cell_size_px}, {"dustbin", o.onnx.dustbin},
        {"score_activation", o.onnx.score_activation},
        {"descriptor_stride_px", o.onnx.descriptor_stride_px},
        {"nms_radius_px", o.onnx.nms_radius_px}, {"threshold", o.onnx.threshold},
        {"border_px", o.onnx.border_px},
        {"normalize_descriptors", o.onnx.normalize_descriptors},
        {"descriptors_layout", o.onnx.descriptors_layout},
        {"keypoint_origin", o.onnx.keypoint_origin}}},
      {"h5",
       {{"path", o.h5.path}, {"descriptor_kind", o.h5.descriptor_kind},
        {"keypoint_origin", o.h5.keypoint_origin}}}};
}

FeatureOptions FeatureOptionsOfMap(const std::string& feature_parameters_json,
                                   const std::string& map_path) {
  const std::string where = map_path + ": feature_parameters";
  nlohmann::json json;
  try {
    json = nlohmann::json::parse(feature_parameters_json);
  } catch (const nlohmann::json::exception&) {
    SLAM_THROW(ConfigError) << where << ": not JSON (the map is damaged; rebuild it)";
  }
  SLAM_THROW_IF_NOT(ConfigError, json.is_object()) << where << ": not a JSON object (rebuild the map)";
  JsonFields fields(json, where);
  return ReadFeatureOptions(fields);
}

}  // namespace duskmap
