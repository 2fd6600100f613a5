// Every feature type, declared once: the only place a type's name and its
// column codes are spelled.
#include "slam/features/feature_registry.h"

#include <utility>

#include "slam/core/check.h"

namespace duskmap {
namespace {

using K = DescriptorKind;

// A detector that needs no file, with its one column, matched by NNDR.
FeatureType Detector(FeatureTypeId id, const char* name, const char* code, DescriptorKind kind) {
  return FeatureType{id, name, {{code, "nndr"}}, kind, std::nullopt, false};
}

// `type`, marked as a learned feature (a trained network).
FeatureType Learned(FeatureType type) {
  type.learned = true;
  return type;
}

// A type that reads a file its options name (`key` under "features.").
FeatureType FileType(FeatureTypeId id, const char* name, std::vector<FeatureColumn> columns,
                     std::optional<DescriptorKind> kind, FeatureFileSpec file) {
  return FeatureType{id, name, std::move(columns), kind, std::move(file), false};
}

std::vector<FeatureType> Declare() {
  std::vector<FeatureType> types = {
      Detector(FeatureTypeId::kSurf, "surf", "SU", K::kFloat),
      Detector(FeatureTypeId::kSift, "sift", "SI", K::kFloat),
      Detector(FeatureTypeId::kBrief, "brief", "BF", K::kBinary),
      Detector(FeatureTypeId::kBrisk, "brisk", "BK", K::kBinary),
      Detector(FeatureTypeId::kKaze, "kaze", "KA", K::kFloat),
      Detector(FeatureTypeId::kDaisy, "daisy", "DY", K::kFloat),
      Detector(FeatureTypeId::kOrb, "orb", "OR", K::kBinary),
      Detector(FeatureTypeId::kAkaze, "akaze", "AK", K::kBinary),
      Detector(FeatureTypeId::kFreak, "freak", "FR", K::kBinary),
      // duskmap's own patch descriptor on SIFT's keypoints (onnx_patch_extractor.h).
      Learned(Detector(FeatureTypeId::kDuskNet, "dusknet", "DN", K::kFloat)),
      // SP and SG: the same SuperPoint features, matched by NNDR or by SuperGlue.
      Learned(FileType(FeatureTypeId::kSuperPoint, "superpoint",
                       {{"SP", "nndr"}, {"SG", "superglue"}}, K::kFloat,
                       {"superpoint.model_path", "", false})),
      // The columns of these two an experiment config declares, with codes of its own.
      FileType(FeatureTypeId::kOnnx, "onnx", {}, K::kFloat,
               {"onnx.model_path", "the model's .onnx file", false}),
      FileType(FeatureTypeId::kH5, "h5", {}, std::nullopt,
               {"h5.path", "the .h5 file (or folder of <session>.h5)", true}),
  };
  for (size_t i = 0; i < types.size(); ++i) {
    SLAM_CHECK_MSG(static_cast<size_t>(types[i].id) == i, "feature types out of FeatureTypeId order");
  }
  return types;
}

}  // namespace

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

}  // namespace duskmap
