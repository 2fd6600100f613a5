// The feature types, each declared once (feature_registry.cc) with what the
// rest of duskmap asks of a type: its name (FeatureOptions::type, the engine
// config's features.type, `features eval --types`), the paper's columns it
// gives (two-letter code and matcher), its descriptors and the file it reads
// besides the images. Its options are its struct in FeatureOptions with the
// paper's defaults (feature_options.h, which also says which option names a
// type's file, FeatureFilePath); its extractor is built by
// CreateFeatureExtractor (feature_factory.h). The options' check, the
// factory, the experiment config's known columns, the engine's checks and
// the feature caches take types from here: adding a type is one entry here,
// one case in the factory (docs/features.md). The registry knows no options
// and no extractor, so that both can take their names from it.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "slam/features/frame_features.h"

namespace duskmap {

// For code that means one type (an extractor's name, SuperGlue's features).
enum class FeatureTypeId { kSurf, kSift, kBrief, kBrisk, kKaze, kDaisy, kOrb, kAkaze, kFreak,
                           kDuskNet, kSuperPoint, kOnnx, kH5 };

// A column of the paper's tables that a type gives.
struct FeatureColumn {
  std::string code;     // two letters: "SU", "SG"
  std::string matcher;  // MatcherOptions::type: "nndr" or "superglue"
};

// The file a type reads besides the images: a model or features.
struct FeatureFileSpec {
  // The option that names it, under "features.": "onnx.model_path"
  // (FeatureFilePath in feature_options.h reads it).
  std::string key;
  // FeatureOptions::Check refuses an empty path with "features.<key>:
  // features of type <name> need <required>"; empty: not checked there (a
  // column of the type says which engine option it needs instead).
  std::string required;
  // A folder of "<session>.h5" files also serves: each session reads its own.
  bool folder_per_session = false;
};

struct FeatureType {
  FeatureTypeId id;
  std::string name;  // FeatureOptions::type, lower case: "surf"
  // The built-in columns (the first has the default matcher); none for the
  // types whose columns an experiment config declares with its own codes.
  std::vector<FeatureColumn> columns;
  // Float (L2) or binary (Hamming) rows; nullopt: as the options declare
  // (h5's descriptor_kind).
  std::optional<DescriptorKind> descriptors;
  std::optional<FeatureFileSpec> file;
  // A learned feature (a trained network: superpoint, dusknet), as the
  // report's findings group them; false for the types a config declares.
  bool learned = false;

  bool DeclaredByConfig() const { return columns.empty(); }
};

// Every type, in the order the CLI lists them: the detectors that need no
// file (surf, sift, brief, brisk, kaze, daisy, orb, akaze, freak, and
// dusknet, whose model is embedded), then superpoint, onnx and h5.
const std::vector<FeatureType>& FeatureTypes();
const FeatureType& FeatureTypeOf(FeatureTypeId id);
const std::string& FeatureTypeName(FeatureTypeId id);
// The default feature type's name (FeatureOptions::type): SURF's.
const std::string& DefaultFeatureTypeName();
// The type named `name` (exact, lower case); nullptr when there is none.
const FeatureType* FindFeatureType(const std::string& name);
// The type that gives the built-in column `code` ("SU"); nullptr when none.
const FeatureType* FindFeatureTypeByCode(const std::string& code);
// The one type whose features `matcher` (MatcherOptions::type) reads, when
// it is a matcher that only a column of that type uses (superglue:
// superpoint); nullptr for a matcher every type can use (nndr).
const FeatureType* FeatureTypeOfMatcher(const std::string& matcher);
// "surf, sift, ..., h5": the names, for "unknown type" errors.
std::string KnownFeatureTypeNames();
// "SU, SI, ..., SG": the built-in columns' codes, for the same.
std::string KnownFeatureColumnCodes();

}  // namespace duskmap
