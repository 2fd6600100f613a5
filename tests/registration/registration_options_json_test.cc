#include "slam/registration/registration_options_json.h"

#include <gtest/gtest.h>

namespace duskmap {
namespace {

TEST(ReadRegistrationOptions, ReadsNestedFieldsAndKeepsDefaults) {
  const nlohmann::json json = nlohmann::json::parse(R"({
    "min_inliers": 25, "second_pass": false,
    "matching": {"float_ratio": 0.8, "search": "kd_tree"},
    "pnp": {"solver": "p3p", "max_reprojection_error_px": 3.0},
    "bundle_adjustment": {"enabled": false},
    "information": {"max_linear_variance_m2": 0.5}})");
  JsonFields fields(json, "test.json:registration");
  const RegistrationOptions o = ReadJsonOptions<RegistrationOptions>(fields);
  EXPECT_EQ(o.min_inliers, 25);
  EXPECT_FALSE(o.second_pass);
  EXPECT_EQ(o.matching.float_ratio, 0.8);
  EXPECT_EQ(o.matching.binary_ratio, 0.8);
  EXPECT_EQ(o.matching.search, NndrSearch::kKdTree);
  EXPECT_EQ(o.pnp.solver, PnpMinimalSolver::kP3P);
  EXPECT_EQ(o.pnp.max_reprojection_error_px, 3.0);
  EXPECT_EQ(o.pnp.max_trials, 300);
  EXPECT_FALSE(o.bundle_adjustment.enabled);
  EXPECT_EQ(o.information.max_linear_variance_m2, 0.5);
  EXPECT_EQ(o.guess_window_px, 40.0);
}

TEST(ReadRegistrationOptions, RejectsUnknownKeysAndBadValuesWithPath) {
  const auto message = [](const char* text) {
    JsonFields fields(nlohmann::json::parse(text), "r.json:registration");
    try {
      ReadJsonOptions<RegistrationOptions>(fields);
    } catch (const ConfigError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message(R"({"pnp": {"max_trails": 10}})"),
            "r.json:registration.pnp: unknown key 'max_trails'");
  EXPECT_NE(message(R"({"matching": {"search": "lsh"}})").find("registration.matching.search"),
            std::string::npos);
  EXPECT_NE(message(R"({"min_inliers": 2})").find("min_inliers"), std::string::npos);
  EXPECT_NE(message(R"({"min_inliers": "many"})").find("wrong type"), std::string::npos);
}

}  // namespace
}  // namespace duskmap
