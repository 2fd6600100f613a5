#include "slam/graph/pose_graph_options_json.h"

#include <gtest/gtest.h>

namespace duskmap {
namespace {

TEST(ReadPoseGraphOptimizerOptions, ReadsFieldsAndRejectsUnknown) {
  JsonFields fields(nlohmann::json::parse(R"({"robust_loss": "huber", "max_error_ratio": 0})"),
                    "g.json:graph");
  const PoseGraphOptimizerOptions o = ReadJsonOptions<PoseGraphOptimizerOptions>(fields);
  EXPECT_EQ(o.robust_loss, RobustLoss::kHuber);
  EXPECT_EQ(o.max_error_ratio, 0.0);
  EXPECT_EQ(o.max_iterations, 20);

  JsonFields unknown(nlohmann::json::parse(R"({"max_error": 3})"), "g.json:graph");
  EXPECT_THROW(ReadJsonOptions<PoseGraphOptimizerOptions>(unknown), ConfigError);
  JsonFields bad_loss(nlohmann::json::parse(R"({"robust_loss": "tukey"})"), "g.json:graph");
  EXPECT_THROW(ReadJsonOptions<PoseGraphOptimizerOptions>(bad_loss), ConfigError);
  JsonFields bad_value(nlohmann::json::parse(R"({"max_iterations": 0})"), "g.json:graph");
  EXPECT_THROW(ReadJsonOptions<PoseGraphOptimizerOptions>(bad_value), ConfigError);
}

}  // namespace
}  // namespace duskmap
