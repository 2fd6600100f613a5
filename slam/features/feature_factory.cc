// CreateFeatureExtractor: the factory by type name.
#include "slam/core/check.h"
#include "slam/features/brief.h"
#include "slam/features/daisy.h"
#include "slam/features/feature_extractor.h"
#include "slam/features/freak.h"
#include "slam/features/h5_extractor.h"
#include "slam/features/onnx_extractor.h"
#include "slam/features/opencv_extractors.h"
#include "slam/features/superpoint.h"
#include "slam/features/surf.h"

namespace duskmap {

std::unique_ptr<FeatureExtractor> CreateFeatureExtractor(const FeatureOptions& o) {
  o.Check();
  const int n = o.max_features;
  const double d = o.max_depth_m;
  if (o.type == "surf") return std::make_unique<SurfExtractor>(o.surf, n, d);
  if (o.type == "sift") return CreateSiftExtractor(o.sift, n, d);
  if (o.type == "brief") return std::make_unique<BriefExtractor>(o.brief, o.gftt, n, d);
  if (o.type == "brisk") return CreateBriskExtractor(o.brisk, n, d);
  if (o.type == "kaze") return CreateKazeExtractor(o.kaze, n, d);
  if (o.type == "daisy") return std::make_unique<DaisyExtractor>(o.daisy, o.surf, n, d);
  if (o.type == "orb") return CreateOrbExtractor(o.orb, n, d);
  if (o.type == "akaze") return CreateAkazeExtractor(o.akaze, n, d);
  if (o.type == "freak") return std::make_unique<FreakExtractor>(o.freak, o.gftt, o.fast, n, d);
  if (o.type == "h5") return std::make_unique<H5FeatureExtractor>(o.h5, n, d);
  if (o.type == "onnx") return std::make_unique<OnnxFeatureExtractor>(o.onnx, n, d);
  SLAM_THROW_IF_NOT(ConfigError, o.type == "superpoint")
      << "features.type: unknown feature type '" << o.type << "'";
  return CreateSuperPointExtractor(o.superpoint, n, d);
}

}  // namespace duskmap
