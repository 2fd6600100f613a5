// Typed options of every feature type, with the paper's settings as defaults
// (spec §1.2 and appendix A: Vis/MaxFeatures 1000, Kp/MaxFeatures 400,
// SURF/HessianThreshold 100, SIFT/ContrastThreshold 0.02, BRISK/Thresh 10,
// ORB/EdgeThreshold 19, ORB/ScaleFactor 2, ORB/NLevels 3, BRIEF/Bytes 32).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "slam/core/json_fields.h"
#include "slam/features/feature_registry.h"

namespace duskmap {

struct SurfOptions {
  double hessian_threshold = 100.0;  // minimum det(H) of the box-filter Hessian (image in 0..255)
  int octaves = 4;                   // number of octaves (filter sizes double per octave)
  int octave_layers = 2;             // layers per octave used for extrema (maps = layers + 2)
  bool extended = false;             // 128-D descriptor instead of 64-D
  bool upright = false;              // U-SURF: no orientation assignment (angle 0)
  void Check() const;
};

struct SiftOptions {
  int octave_layers = 3;            // layers per octave
  double contrast_threshold = 0.02;  // DoG contrast threshold (paper's runs)
  double edge_threshold = 10.0;     // principal-curvature ratio limit
  double sigma = 1.6;               // base blur, pixels
  bool root_sift = false;           // L1-normalise then square-root each descriptor
  void Check() const;
};

struct OrbOptions {
  double scale_factor = 2.0;  // pyramid decimation ratio
  int levels = 3;             // pyramid levels
  int edge_threshold = 19;    // border without features, pixels
  int patch_size = 31;        // oriented BRIEF patch, pixels
  int fast_threshold = 20;    // FAST intensity threshold, grey levels
  void Check() const;
};

struct BriskOptions {
  int threshold = 10;          // AGAST threshold, grey levels (paper's runs)
  int octaves = 3;             // detection octaves
  double pattern_scale = 1.0;  // sampling pattern scale
  void Check() const;
};

struct KazeOptions {
  bool extended = false;     // 128-D instead of 64-D
  bool upright = false;      // no orientation
  double threshold = 0.001;  // detector response threshold
  int octaves = 4;           // octaves
  int octave_layers = 4;     // sublevels per octave
  // Describe in the detection pass (one detectAndCompute, then the strongest
  // kept) instead of the reference's detect, limit, compute: one nonlinear
  // scale space instead of two, and the orientations the detector assigns
  // (OpenCV's compute assigns others). Not the paper's setting.
  bool single_pass = false;
  void Check() const;
};

struct AkazeOptions {
  double threshold = 0.001;  // detector response threshold
  int octaves = 4;           // octaves
  int octave_layers = 4;     // sublevels per octave
  void Check() const;
};

// Corner detectors the binary descriptors run on.
struct GfttOptions {
  double quality_level = 0.001;  // relative to the best corner's min eigenvalue
  double min_distance_px = 7.0;  // minimum distance between corners, pixels
  int block_size = 3;            // covariance window, pixels
  void Check() const;
};

struct FastOptions {
  int threshold = 20;  // intensity threshold, grey levels
  void Check() const;
};

struct BriefOptions {
  int bytes = 32;            // descriptor length: 16, 32 or 64 bytes
  int patch_size_px = 48;    // side of the square test patch, pixels
  double smooth_sigma_px = 2.0;  // Gaussian pre-smoothing, pixels (9x9 kernel)
  uint64_t pattern_seed = 20100905;  // seed of the fixed Gaussian test pattern
  void Check() const;
};

struct DaisyOptions {
  double radius_px = 15.0;  // radius of the outermost ring, pixels
  int rings = 3;            // rings of histograms around the centre
  int ring_points = 8;      // histograms per ring
  int orientations = 8;     // orientation bins per histogram
  bool normalize = false;   // unit-normalise each histogram (Tola et al.'s partial normalisation;
                            // off in OpenCV's default, which the paper's runs used)
  bool use_orientation = false;  // rotate the grid to the keypoint angle (OpenCV default: off)
  void Check() const;
};

struct FreakOptions {
  std::string detector = "gftt";  // keypoints: "gftt" (RTAB-Map type 5) or "fast" (type 3)
  bool orientation_normalized = true;  // rotate the pattern to the 45-pair orientation
  bool scale_normalized = true;        // scale the pattern with the keypoint size
  double pattern_scale = 22.0;         // outer pattern radius is 2/3 of this at scale 1, pixels
  void Check() const;
};

struct SuperPointOptions {
  std::string model_path;       // ONNX file (input 1x1xHxW gray/255; outputs semi, desc)
  double threshold = 0.010;     // minimum heat-map score
  int nms_radius_px = 4;        // max-pool non-maximum suppression radius, pixels
  int border_px = 4;            // keypoints closer than this to the border are removed
  void Check() const;
};

// A local-feature network in an ONNX file, run through OpenCV's DNN module
// (onnx_extractor.h). The options declare the model's contract: its input and
// one of two output shapes. The defaults are SuperPoint's (superpoint.h).
//   dense:  a score map and a descriptor map. Scores come as "cells" (per
//           cell of cell_size_px², that many logit channels plus an optional
//           dustbin, softmax over the channels: SuperPoint, XFeat) or as one
//           full-resolution "map" channel (ALIKED, DISK); keypoints are its
//           max-pool NMS maxima above threshold, descriptors bilinear samples
//           of the map at 1/descriptor_stride_px.
//   sparse: keypoints (1xNx2 or Nx2, x then y), descriptors (1xNxD or NxD,
//           or DxN with descriptors_layout "d_by_n") and optional scores (N).
//   patch:  a patch descriptor network (onnx_patch_extractor.h): keypoints
//           from `detector`, patches from PatchSampler (patch_sampler.h),
//           input Nx1xPxP (P = patch_size_px), output NxD, in batches.
// OpenCV 4.6 imports no TopK, so a model that selects its keypoints with it
// must be exported with its dense outputs instead.
struct OnnxFeatureOptions {
  std::string model_path;
  std::string contract = "dense";  // "dense", "sparse" or "patch"
  // Input blob 1xCxHxW: C = 1 ("gray") or 3 ("rgb", "bgr": channel order);
  // value = (pixel * input_scale - input_mean[c]) / input_std[c], the image
  // padded (border replicated) to multiples of input_multiple_px.
  std::string input_color = "gray";
  double input_scale = 1.0 / 255.0;
  std::vector<double> input_mean = {0.0};  // one value, or one per channel
  std::vector<double> input_std = {1.0};   // one value, or one per channel, > 0
  int input_multiple_px = 8;
  // Output names; empty: dense outputs found by their shape, sparse ones
  // named "keypoints", "descriptors" and (when the model has it) "scores".
  std::string scores_output;
  std::string descriptors_output;
  std::string keypoints_output;  // sparse only
  int descriptor_dims = 0;       // 0: any; else the descriptors must have this many
  // Dense decoding.
  std::string score_layout = "cells";     // "cells" or "map"
  int cell_size_px = 8;                   // cells: channels = cell_size_px² (+1 dustbin)
  bool dustbin = true;                    // cells: the last channel means "no keypoint"
  std::string score_activation = "none";  // map: "none" or "sigmoid"
  int descriptor_stride_px = 8;           // the descriptor map's pixels per cell
  int nms_radius_px = 4;                  // max-pool NMS radius (dense), pixels
  // Both contracts.
  double threshold = 0.010;      // keypoints need a score above this (sparse: with scores)
  int border_px = 4;             // keypoints closer than this to the border are removed
  bool normalize_descriptors = true;  // L2-normalise every descriptor
  std::string descriptors_layout = "n_by_d";     // sparse: "n_by_d" or "d_by_n"
  std::string keypoint_origin = "pixel_centre";  // sparse: "pixel_centre" or "pixel_corner"
  // Patch contract (threshold and border_px unused: the detector's keypoints are kept).
  std::string detector = "dog";  // "dog": the sift type's keypoints (FeatureOptions::sift)
  int patch_size_px = 32;        // P: the model's input is Nx1xPxP
  double support_per_size = 6.0;  // patch side in image pixels per pixel of KeyPoint::size
  bool oriented = true;          // patches turned by KeyPoint::angle
  int batch_size = 256;          // patches per forward pass
  void Check() const { CheckAs(FeatureTypeId::kOnnx); }
  // Errors name the option under `type`'s section ("features.dusknet.batch_size").
  void CheckAs(FeatureTypeId type) const;
};

// The options of the built-in dusknet type: the patch contract of the
// committed model (slam/features/models/dusknet.onnx; model_path "" = the
// model embedded at build time, embedded_model.h): 32x32 patches of 6 sizes,
// oriented, value = pixel / 255, 128-D output.
OnnxFeatureOptions DuskNetFeatureOptions();

// Features imported from a file in hloc's HDF5 layout (h5_feature_file.h).
struct H5FeatureOptions {
  // A .h5 file for the whole dataset, with one group per image named
  // "<session>/<image name>" ("1/rgb/60360.000000.png"), or a folder with one
  // "<session>.h5" per session whose groups are named "<image name>".
  std::string path;
  std::string descriptor_kind = "float";         // "float" (L2) or "binary" (Hamming): checked against the file's dtype
  std::string keypoint_origin = "pixel_centre";  // "pixel_centre" (OpenCV, hloc) or "pixel_corner" (COLMAP)
  void Check() const;
};

// Which extractor to build and its options. `type` is one of
// FeatureTypeNames() (the types of feature_registry.h); only the sub-options
// of that type are used.
struct FeatureOptions {
  std::string type = DefaultFeatureTypeName();  // SURF (feature_registry.h)
  int max_features = 1000;        // Vis/MaxFeatures: kept per frame, strongest first
  int vocabulary_features = 400;  // Kp/MaxFeatures: the first rows quantized into words
  double max_depth_m = 0.0;       // 3D points beyond this depth are NaN; 0 = no limit
  SurfOptions surf;
  SiftOptions sift;
  OrbOptions orb;
  BriskOptions brisk;
  KazeOptions kaze;
  AkazeOptions akaze;
  GfttOptions gftt;
  FastOptions fast;
  BriefOptions brief;
  DaisyOptions daisy;
  FreakOptions freak;
  SuperPointOptions superpoint;
  OnnxFeatureOptions onnx;
  H5FeatureOptions h5;
  OnnxFeatureOptions dusknet = DuskNetFeatureOptions();
  void Check() const;
};

// The path of the file that options.type reads besides the images, from the
// option that names it (FeatureFileSpec::key: superpoint.model_path,
// onnx.model_path, h5.path; and dusknet.model_path, which overrides the
// embedded model); empty for a type that reads none or an unknown type.
const std::string& FeatureFilePath(const FeatureOptions& options);

// The names of FeatureTypes() (feature_registry.h), in its order.
const std::vector<std::string>& FeatureTypeNames();

// The types that need no file (every type but superpoint, onnx and h5, which
// need a model or an .h5): the default of `duskmap features eval`.
const std::vector<std::string>& BuiltInFeatureTypeNames();

// `name` in any case ("SURF", "Sift") as its FeatureTypeNames() spelling;
// ConfigError "<where>: unknown feature type '<name>' (known: ...)".
std::string FeatureTypeFromName(const std::string& name, const std::string& where);

// JSON: slam/features/feature_options_json.h.

}  // namespace duskmap
