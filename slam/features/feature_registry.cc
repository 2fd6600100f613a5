// Every feature type, declared once: the only place a type's name and its
// column codes are spelled.
#include "slam/features/feature_registry.h"

#include <utility>

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
namespace {

using Extractor = std::unique_ptr<FeatureExtractor>;
using Factory = Extractor (*)(const FeatureOptions&);
using K = DescriptorKind;
using O = FeatureOptions;

// A detector that needs no file, with its one column, matched by NNDR.
FeatureType Detector(FeatureTypeId id, const char* name, const char* code, DescriptorKind kind,
                     Factory create) {
  return FeatureType{id, name, {{code, "nndr"}}, kind, std::nullopt, create};
}

// A type that reads a file its options name (`key` under "features.").
FeatureType FileType(FeatureTypeId id, const char* name, std::vector<FeatureColumn> columns,
                     std::optional<DescriptorKind> kind, FeatureFileSpec file, Factory create) {
  return FeatureType{id, name, std::move(columns), kind, std::move(file), create};
}

std::vector<FeatureType> Declare() {
  std::vector<FeatureType> types = {
      Detector(FeatureTypeId::kSurf, "surf", "SU", K::kFloat, [](const O& o) -> Extractor {
        return std::make_unique<SurfExtractor>(o.surf, o.max_features, o.max_depth_m);
      }),
      Detector(FeatureTypeId::kSift, "sift", "SI", K::kFloat, [](const O& o) {
        return CreateSiftExtractor(o.sift, o.max_features, o.max_depth_m);
      }),
      Detector(FeatureTypeId::kBrief, "brief", "BF", K::kBinary, [](const O& o) -> Extractor {
        return std::make_unique<BriefExtractor>(o.brief, o.gftt, o.max_features, o.max_depth_m);
      }),
      Detector(FeatureTypeId::kBrisk, "brisk", "BK", K::kBinary, [](const O& o) {
        return CreateBriskExtractor(o.brisk, o.max_features, o.max_depth_m);
      }),
      Detector(FeatureTypeId::kKaze, "kaze", "KA", K::kFloat, [](const O& o) {
        return CreateKazeExtractor(o.kaze, o.max_features, o.max_depth_m);
      }),
      Detector(FeatureTypeId::kDaisy, "daisy", "DY", K::kFloat, [](const O& o) -> Extractor {
        return std::make_unique<DaisyExtractor>(o.daisy, o.surf, o.max_features, o.max_depth_m);
      }),
      Detector(FeatureTypeId::kOrb, "orb", "OR", K::kBinary, [](const O& o) {
        return CreateOrbExtractor(o.orb, o.max_features, o.max_depth_m);
      }),
      Detector(FeatureTypeId::kAkaze, "akaze", "AK", K::kBinary, [](const O& o) {
        return CreateAkazeExtractor(o.akaze, o.max_features, o.max_depth_m);
      }),
      Detector(FeatureTypeId::kFreak, "freak", "FR", K::kBinary, [](const O& o) -> Extractor {
        return std::make_unique<FreakExtractor>(o.freak, o.gftt, o.fast, o.max_features,
                                                o.max_depth_m);
      }),
      // SP and SG: the same SuperPoint features, matched by NNDR or by SuperGlue.
      FileType(FeatureTypeId::kSuperPoint, "superpoint", {{"SP", "nndr"}, {"SG", "superglue"}},
               K::kFloat,
               {[](const O& o) -> const std::string& { return o.superpoint.model_path; },
                "superpoint.model_path", "", false},
               [](const O& o) {
                 return CreateSuperPointExtractor(o.superpoint, o.max_features, o.max_depth_m);
               }),
      // The columns of these two an experiment config declares, with codes of its own.
      FileType(FeatureTypeId::kOnnx, "onnx", {}, K::kFloat,
               {[](const O& o) -> const std::string& { return o.onnx.model_path; },
                "onnx.model_path", "the model's .onnx file", false},
               [](const O& o) -> Extractor {
                 return std::make_unique<OnnxFeatureExtractor>(o.onnx, o.max_features,
                                                               o.max_depth_m);
               }),
      FileType(FeatureTypeId::kH5, "h5", {}, std::nullopt,
               {[](const O& o) -> const std::string& { return o.h5.path; }, "h5.path",
                "the .h5 file (or folder of <session>.h5)", true},
               [](const O& o) -> Extractor {
                 return std::make_unique<H5FeatureExtractor>(o.h5, o.max_features, o.max_depth_m);
               }),
  };
  for (size_t i = 0; i < types.size(); ++i) {
    SLAM_CHECK_MSG(static_cast<size_t>(types[i].id) == i, "feature types out of FeatureTypeId order");
  }
  return types;
}

}  // namespace

FeatureOptions FeatureType::Defaults() const {
  FeatureOptions options;
  options.type = name;
  return options;
}

const std::vector<FeatureType>& FeatureTypes() {
  static const std::vector<FeatureType> kTypes = Declare();
  return kTypes;
}

const FeatureType& FeatureTypeOf(FeatureTypeId id) { return FeatureTypes().at(static_cast<size_t>(id)); }

const std::string& FeatureTypeName(FeatureTypeId id) { return FeatureTypeOf(id).name; }

const std::string& DefaultFeatureTypeName() { return FeatureTypeName(FeatureTypeId::kSurf); }

const FeatureType* FindFeatureType(const std::string& name) {
  for (const FeatureType& type : FeatureTypes()) {
    if (type.name == name) return &type;
  }
  return nullptr;
}

const FeatureType* FindFeatureTypeByCode(const std::string& code) {
  for (const FeatureType& type : FeatureTypes()) {
    for (const FeatureColumn& column : type.columns) {
      if (column.code == code) return &type;
    }
  }
  return nullptr;
}

const FeatureType* FeatureTypeOfMatcher(const std::string& matcher) {
  for (const FeatureType& type : FeatureTypes()) {
    for (size_t i = 1; i < type.columns.size(); ++i) {  // the first column's is the default
      if (type.columns[i].matcher == matcher) return &type;
    }
  }
  return nullptr;
}

std::string KnownFeatureTypeNames() {
  std::string known;
  for (const FeatureType& type : FeatureTypes()) known += (known.empty() ? "" : ", ") + type.name;
  return known;
}

std::string KnownFeatureColumnCodes() {
  std::string known;
  for (const FeatureType& type : FeatureTypes()) {
    for (const FeatureColumn& column : type.columns) known += (known.empty() ? "" : ", ") + column.code;
  }
  return known;
}

std::unique_ptr<FeatureExtractor> CreateFeatureExtractor(const FeatureOptions& options) {
  options.Check();  // the type is known
  return FindFeatureType(options.type)->create(options);
}

}  // namespace duskmap
