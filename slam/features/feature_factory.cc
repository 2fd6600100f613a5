#include "slam/features/feature_factory.h"

#include "slam/core/check.h"
#include "slam/features/brief.h"
#include "slam/features/daisy.h"
#include "slam/features/feature_registry.h"
#include "slam/features/freak.h"
#include "slam/features/h5_extractor.h"
#include "slam/features/onnx_extractor.h"
#include "slam/features/onnx_patch_extractor.h"
#include "slam/features/opencv_extractors.h"
#include "slam/features/superpoint.h"
#include "slam/features/surf.h"

namespace duskmap {

std::unique_ptr<FeatureExtractor> CreateFeatureExtractor(const FeatureOptions& options) {
  options.Check();  // the type is known
  const FeatureOptions& o = options;
  switch (FindFeatureType(options.type)->id) {
    case FeatureTypeId::kSurf:
      return std::make_unique<SurfExtractor>(o.surf, o.max_features, o.max_depth_m);
    case FeatureTypeId::kSift:
      return CreateSiftExtractor(o.sift, o.max_features, o.max_depth_m);
    case FeatureTypeId::kBrief:
      return std::make_unique<BriefExtractor>(o.brief, o.gftt, o.max_features, o.max_depth_m);
    case FeatureTypeId::kBrisk:
      return CreateBriskExtractor(o.brisk, o.max_features, o.max_depth_m);
    case FeatureTypeId::kKaze:
      return CreateKazeExtractor(o.kaze, o.max_features, o.max_depth_m);
    case FeatureTypeId::kDaisy:
      return std::make_unique<DaisyExtractor>(o.daisy, o.surf, o.max_features, o.max_depth_m);
    case FeatureTypeId::kOrb:
      return CreateOrbExtractor(o.orb, o.max_features, o.max_depth_m);
    case FeatureTypeId::kAkaze:
      return CreateAkazeExtractor(o.akaze, o.max_features, o.max_depth_m);
    case FeatureTypeId::kFreak:
      return std::make_unique<FreakExtractor>(o.freak, o.gftt, o.fast, o.max_features,
                                              o.max_depth_m);
    case FeatureTypeId::kSuperPoint:
      return CreateSuperPointExtractor(o.superpoint, o.max_features, o.max_depth_m);
    case FeatureTypeId::kDuskNet:
      return std::make_unique<OnnxPatchExtractor>(o.dusknet, o.sift, o.max_features, o.max_depth_m,
                                                  FeatureTypeId::kDuskNet);
    case FeatureTypeId::kOnnx:
      if (o.onnx.contract == "patch") {
        return std::make_unique<OnnxPatchExtractor>(o.onnx, o.sift, o.max_features, o.max_depth_m);
      }
      return std::make_unique<OnnxFeatureExtractor>(o.onnx, o.max_features, o.max_depth_m);
    case FeatureTypeId::kH5:
      return std::make_unique<H5FeatureExtractor>(o.h5, o.max_features, o.max_depth_m);
  }
  SLAM_CHECK_MSG(false, "feature type without a factory: " + options.type);
}

}  // namespace duskmap
