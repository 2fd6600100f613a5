// The feature registry: every type once, with a unique name and codes, the
// factory that builds it, and the lookups the config, engine and caches use.
#include "slam/features/feature_registry.h"

#include <cctype>
#include <set>

#include <gtest/gtest.h>

#include "slam/features/feature_factory.h"
#include "slam/features/feature_options_json.h"
#include "tests/testing/error_of.h"

namespace duskmap {
namespace {

// FeatureOptions' defaults with `type`.
FeatureOptions DefaultsOf(const FeatureType& type) {
  FeatureOptions options;
  options.type = type.name;
  return options;
}

TEST(FeatureRegistry, EveryTypeHasAUniqueNameAndUniqueCodes) {
  std::set<std::string> names, codes;
  for (size_t i = 0; i < FeatureTypes().size(); ++i) {
    const FeatureType& type = FeatureTypes()[i];
    EXPECT_EQ(static_cast<size_t>(type.id), i) << type.name;
    EXPECT_EQ(&FeatureTypeOf(type.id), &type) << type.name;
    EXPECT_TRUE(names.insert(type.name).second) << "name listed twice: " << type.name;
    EXPECT_FALSE(type.name.empty());
    for (char c : type.name) EXPECT_FALSE(std::isupper(static_cast<unsigned char>(c))) << type.name;
    for (const FeatureColumn& column : type.columns) {
      EXPECT_EQ(column.code.size(), 2u) << column.code;
      EXPECT_TRUE(codes.insert(column.code).second) << "code listed twice: " << column.code;
      EXPECT_TRUE(column.matcher == "nndr" || column.matcher == "superglue") << column.matcher;
    }
    // A type without built-in columns is declared by configs with a file of its own.
    if (type.DeclaredByConfig()) {
      ASSERT_TRUE(type.file.has_value()) << type.name;
      EXPECT_FALSE(type.file->required.empty()) << type.name;
    }
  }
  EXPECT_EQ(names.size(), 13u);
  EXPECT_EQ(codes.size(), 12u);  // the paper's eight columns, OR, AK, FR and DN
  EXPECT_EQ(FeatureTypeNames().size(), FeatureTypes().size());
  EXPECT_EQ(DefaultFeatureTypeName(), FeatureTypes().front().name);
  EXPECT_EQ(FeatureOptions().type, DefaultFeatureTypeName());
}

// Each type that needs no file is built by its factory, as the type it is
// declared as: its name, and the descriptors it declares.
TEST(FeatureRegistry, TheFactoryBuildsEveryTypeThatNeedsNoFile) {
  int built = 0;
  for (const FeatureType& type : FeatureTypes()) {
    if (type.file) continue;
    const FeatureOptions options = DefaultsOf(type);
    EXPECT_EQ(options.type, type.name);
    const std::unique_ptr<FeatureExtractor> extractor = CreateFeatureExtractor(options);
    ASSERT_NE(extractor, nullptr) << type.name;
    EXPECT_EQ(extractor->name(), type.name);
    ASSERT_TRUE(type.descriptors.has_value()) << type.name;
    EXPECT_EQ(extractor->kind(), *type.descriptors) << type.name;
    ++built;
  }
  EXPECT_EQ(built, static_cast<int>(BuiltInFeatureTypeNames().size()));
  EXPECT_EQ(built, 10);
}

// The types that read a file are refused without it, by the option that names it.
TEST(FeatureRegistry, TypesThatReadAFileNameTheOptionWithoutIt) {
  for (const FeatureType& type : FeatureTypes()) {
    if (!type.file) continue;
    const FeatureOptions options = DefaultsOf(type);
    EXPECT_TRUE(FeatureFilePath(options).empty()) << type.name;
    const std::string error = testing::ErrorOf([&] { CreateFeatureExtractor(options); });
    EXPECT_NE(error.find("features." + type.file->key), std::string::npos) << error;
    // FeatureFilePath reads the option the registry names: set at its key, it is the path.
    const size_t dot = type.file->key.find('.');
    const nlohmann::json json = {{"type", type.name},
                                 {type.file->key.substr(0, dot), {{type.file->key.substr(dot + 1), "file"}}}};
    EXPECT_EQ(FeatureFilePath(ReadJsonOptions<FeatureOptions>(json, "features")), "file") << type.name;
  }
}

// DN: duskmap's learned descriptor, a built-in float type matched by NNDR;
// the learned flag is set for it and SuperPoint only.
TEST(FeatureRegistry, DuskNetIsABuiltInLearnedType) {
  const FeatureType* type = FindFeatureTypeByCode("DN");
  ASSERT_NE(type, nullptr);
  EXPECT_EQ(type->id, FeatureTypeId::kDuskNet);
  EXPECT_EQ(type->name, "dusknet");
  EXPECT_EQ(type->columns.size(), 1u);
  EXPECT_EQ(type->columns[0].matcher, "nndr");
  EXPECT_EQ(type->descriptors, DescriptorKind::kFloat);
  EXPECT_FALSE(type->file.has_value());  // its model is embedded
  std::set<std::string> learned;
  for (const FeatureType& t : FeatureTypes()) {
    if (t.learned) learned.insert(t.name);
  }
  EXPECT_EQ(learned, (std::set<std::string>{"dusknet", "superpoint"}));
}

TEST(FeatureRegistry, LooksTypesUpByNameAndByCode) {
  ASSERT_NE(FindFeatureType("kaze"), nullptr);
  EXPECT_EQ(FindFeatureType("kaze")->id, FeatureTypeId::kKaze);
  EXPECT_EQ(FindFeatureType("KAZE"), nullptr);  // names are exact; FeatureTypeFromName folds case
  EXPECT_EQ(FindFeatureType("surface"), nullptr);
  EXPECT_EQ(FeatureTypeFromName("KAZE", "--types"), "kaze");
  EXPECT_EQ(FeatureTypeFromName("SuperPoint", "--types"), "superpoint");

  ASSERT_NE(FindFeatureTypeByCode("KA"), nullptr);
  EXPECT_EQ(FindFeatureTypeByCode("KA")->name, "kaze");
  EXPECT_EQ(FindFeatureTypeByCode("SG"), &FeatureTypeOf(FeatureTypeId::kSuperPoint));
  EXPECT_EQ(FindFeatureTypeByCode("ka"), nullptr);  // codes are exact, as in configs
  EXPECT_EQ(FindFeatureTypeByCode("MY"), nullptr);

  EXPECT_EQ(FeatureTypeOfMatcher("superglue"), &FeatureTypeOf(FeatureTypeId::kSuperPoint));
  EXPECT_EQ(FeatureTypeOfMatcher("nndr"), nullptr);
}

// Unknown names are answered with every known one, from the registry.
TEST(FeatureRegistry, UnknownTypesListTheKnownOnes) {
  EXPECT_EQ(KnownFeatureTypeNames(),
            "surf, sift, brief, brisk, kaze, daisy, orb, akaze, freak, dusknet, superpoint, onnx, h5");
  EXPECT_EQ(KnownFeatureColumnCodes(), "SU, SI, BF, BK, KA, DY, OR, AK, FR, DN, SP, SG");
  FeatureOptions options;
  options.type = "SU";
  const std::string error = testing::ErrorOf([&] { options.Check(); });
  EXPECT_EQ(error,
            "features.type: unknown feature type 'SU' (known: " + KnownFeatureTypeNames() +
                "; experiment configs use the paper's column codes instead: " +
                KnownFeatureColumnCodes() + ")");
}

}  // namespace
}  // namespace duskmap
