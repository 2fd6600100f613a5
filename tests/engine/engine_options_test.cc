#include "slam/engine/engine_options.h"

#include <gtest/gtest.h>

#include "slam/core/check.h"

namespace duskmap {
namespace {

TEST(ReadEngineOptions, ReadsNestedValues) {
  const auto json = nlohmann::json::parse(R"({
    "features": {"type": "sift", "vocabulary_features": 300},
    "registration": {"min_inliers": 15},
    "loop_closure": {"loop_threshold": 0.2,
                     "vocabulary": {"index": {"float_storage": "float32"}}},
    "proximity": {"local_radius_m": 2.0},
    "mapping": {"reduce_graph": true},
    "localization": {"proximity_max_paths": 2},
    "random_seed": 9})");
  JsonFields fields(json, "engine.json");
  const EngineOptions o = ReadEngineOptions(fields);
  EXPECT_EQ(o.features.type, "sift");
  EXPECT_EQ(o.registration.min_inliers, 15);
  EXPECT_TRUE(o.mapping.reduce_graph);
  EXPECT_EQ(o.LoopClosure().vocabulary.max_features_per_node, 300);
  EXPECT_DOUBLE_EQ(o.LoopClosure().loop_threshold, 0.2);
  EXPECT_EQ(o.LoopClosure().vocabulary.index.float_storage, DescriptorStorage::kFloat32);
  EXPECT_EQ(o.LocalizationProximity().max_paths, 2);
  EXPECT_EQ(o.MappingProximity().max_paths, 3);
  EXPECT_DOUBLE_EQ(o.MappingProximity().local_radius_m, 2.0);
  EXPECT_EQ(o.Registration().pnp.random_seed, 9u);
}

TEST(EngineOptions, DefaultsAreThePapersSettings) {
  // configs/engine_paper.json (the paper's runs) and the built-in defaults
  // must agree, so a config without engine_config runs the paper's settings.
  const EngineOptions paper =
      ReadEngineOptionsFile(std::string(DUSKMAP_SOURCE_DIR) + "/configs/engine_paper.json");
  EXPECT_EQ(EngineOptionsToJson(EngineOptions()).dump(2), EngineOptionsToJson(paper).dump(2));
  EXPECT_DOUBLE_EQ(EngineOptions().optimizer.max_error_ratio, 0.0);
  EXPECT_DOUBLE_EQ(EngineOptions().loop_closure.vocabulary.bad_signature_ratio, 0.2);
  EXPECT_EQ(EngineOptions().loop_closure.vocabulary.index.float_storage, DescriptorStorage::kUint8);
  // Kp/ByteToFloat true: binary descriptors by the L1 of their bytes, in the
  // vocabulary and in registration's first pass.
  EXPECT_EQ(paper.binary_distance, BinaryDistance::kByteL1);
  EXPECT_EQ(paper.LoopClosure().vocabulary.index.binary_distance, BinaryDistance::kByteL1);
  EXPECT_EQ(paper.Registration().matching.binary_distance, BinaryDistance::kByteL1);
  JsonFields hamming(nlohmann::json::parse(R"({"binary_distance": "hamming"})"), "engine.json");
  const EngineOptions exact = ReadEngineOptions(hamming);
  EXPECT_EQ(exact.LoopClosure().vocabulary.index.binary_distance, BinaryDistance::kHamming);
  EXPECT_EQ(exact.Registration().matching.binary_distance, BinaryDistance::kHamming);
  JsonFields unknown(nlohmann::json::parse(R"({"binary_distance": "l2"})"), "engine.json");
  EXPECT_THROW(ReadEngineOptions(unknown), ConfigError);
  JsonFields bad(nlohmann::json::parse(R"({"loop_closure": {"vocabulary": {"index": {"float_storage": "int4"}}}})"), "engine.json");
  EXPECT_THROW(ReadEngineOptions(bad), ConfigError);
}

TEST(ReadEngineOptions, EveryKeyOfEverySubStructCanBeSet) {
  const auto json = nlohmann::json::parse(R"({
    "registration": {"pnp": {"max_trials": 500, "solver": "p3p"},
                     "matching": {"float_ratio": 0.7, "search": "brute_force"},
                     "bundle_adjustment": {"enabled": false},
                     "information": {"variance_median_ratio": 2}},
    "loop_closure": {"vocabulary": {"nndr_ratio": 0.7, "index": {"checks": 64}},
                     "bayes": {"virtual_place_prior": 0.8}, "top_hypotheses": 3},
    "proximity": {"max_path_depth": 20, "forward_axis": [1, 0, 0]},
    "optimizer": {"robust_loss": "huber", "num_threads": 2},
    "matcher": {"superglue": {"match_threshold": 0.3}},
    "features": {"sift": {"root_sift": true}}})");
  JsonFields fields(json, "engine.json");
  const EngineOptions o = ReadEngineOptions(fields);
  EXPECT_EQ(o.Registration().pnp.max_trials, 500);
  EXPECT_EQ(o.Registration().pnp.solver, PnpMinimalSolver::kP3P);
  EXPECT_DOUBLE_EQ(o.Registration().matching.float_ratio, 0.7);
  EXPECT_EQ(o.Registration().matching.search, NndrSearch::kBruteForce);
  EXPECT_FALSE(o.Registration().bundle_adjustment.enabled);
  EXPECT_EQ(o.Registration().information.variance_median_ratio, 2);
  EXPECT_DOUBLE_EQ(o.LoopClosure().vocabulary.nndr_ratio, 0.7);
  EXPECT_EQ(o.LoopClosure().vocabulary.index.checks, 64);
  EXPECT_DOUBLE_EQ(o.LoopClosure().bayes.virtual_place_prior, 0.8);
  EXPECT_EQ(o.LoopClosure().top_hypotheses, 3);
  EXPECT_EQ(o.MappingProximity().max_path_depth, 20);
  EXPECT_TRUE(o.MappingProximity().forward_axis.isApprox(Eigen::Vector3d::UnitX()));
  EXPECT_EQ(o.optimizer.robust_loss, RobustLoss::kHuber);
  EXPECT_EQ(o.optimizer.num_threads, 2);
  EXPECT_DOUBLE_EQ(o.matcher.superglue.match_threshold, 0.3);
  EXPECT_TRUE(o.features.sift.root_sift);
  // The options written are the options read, key for key.
  JsonFields written(EngineOptionsToJson(o), "written");
  EXPECT_EQ(EngineOptionsToJson(ReadEngineOptions(written)), EngineOptionsToJson(o));
}

std::string ReadError(const char* text) {
  JsonFields fields(nlohmann::json::parse(text), "engine.json");
  try {
    ReadEngineOptions(fields);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "no error";
}

TEST(ReadEngineOptions, RefusesWhatTheEngineSetsItselfNamingTheKeyThatDoes) {
  EXPECT_EQ(ReadError(R"({"registration": {"pnp": {"random_seed": 3}}})"),
            "engine.json.registration.pnp.random_seed: not set here; random_seed sets it");
  EXPECT_EQ(ReadError(R"({"loop_closure": {"vocabulary": {"max_features_per_node": 9}}})"),
            "engine.json.loop_closure.vocabulary.max_features_per_node: not set here; "
            "features.vocabulary_features sets it");
  EXPECT_EQ(ReadError(R"({"registration": {"matching": {"binary_distance": "hamming"}}})"),
            "engine.json.registration.matching.binary_distance: not set here; binary_distance "
            "sets it");
  EXPECT_NE(ReadError(R"({"proximity": {"max_paths": 1}})").find("mapping.proximity_max_paths"),
            std::string::npos);
  // ... and the writer leaves them out.
  const nlohmann::json written = EngineOptionsToJson(EngineOptions());
  EXPECT_FALSE(written["registration"]["pnp"].contains("random_seed"));
  EXPECT_FALSE(written["loop_closure"].contains("short_term_memory_size"));
  EXPECT_FALSE(written["proximity"].contains("max_paths"));
  EXPECT_TRUE(written["registration"]["pnp"].contains("max_trials"));
}

TEST(ReadEngineOptions, NamesTheNewKeyOfAnOldOne) {
  EXPECT_EQ(ReadError(R"({"registration": {"float_nndr_ratio": 0.6}})"),
            "engine.json.registration.float_nndr_ratio: renamed registration.matching.float_ratio");
  EXPECT_EQ(ReadError(R"({"loop_closure": {"word_storage": "uint8"}})"),
            "engine.json.loop_closure.word_storage: renamed "
            "loop_closure.vocabulary.index.float_storage");
}

TEST(ReadEngineOptions, ACheckFailureNamesTheJsonPath) {
  EXPECT_NE(ReadError(R"({"registration": {"pnp": {"max_trials": 0}}})")
                .find("engine.json: registration.pnp.max_trials"),
            std::string::npos)
      << ReadError(R"({"registration": {"pnp": {"max_trials": 0}}})");
  EXPECT_NE(ReadError(R"({"loop_closure": {"vocabulary": {"index": {"checks": 0}}}})")
                .find("engine.json: loop_closure.vocabulary.index.checks"),
            std::string::npos)
      << ReadError(R"({"loop_closure": {"vocabulary": {"index": {"checks": 0}}}})");
}

TEST(ReadEngineOptions, RejectsUnknownKeysWithPath) {
  JsonFields fields(nlohmann::json::parse(R"({"mapping": {"reduce": true}})"), "engine.json");
  try {
    ReadEngineOptions(fields);
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("engine.json.mapping"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("reduce"), std::string::npos) << e.what();
  }
}

TEST(EngineOptions, CheckNamesField) {
  EngineOptions o;
  o.localization.odometry_cache_size = -1;
  EXPECT_THROW(o.Check(), ConfigError);
  o.localization.odometry_cache_size = 1;  // a cache needs two frames
  EXPECT_THROW(o.Check(), ConfigError);
  o.localization.odometry_cache_size = 10;
  EXPECT_NO_THROW(o.Check());
  o.localization.odometry_cache_max_error_ratio = 0.0;
  EXPECT_THROW(o.Check(), ConfigError);
  o = EngineOptions();
  o.odometry.linear_sigma_m = 0.0;
  try {
    o.Check();
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("linear_sigma_m"), std::string::npos);
  }
}

}  // namespace
}  // namespace duskmap
