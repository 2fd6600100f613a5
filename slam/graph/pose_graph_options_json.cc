#include "slam/graph/pose_graph_options_json.h"

#include <string>

namespace duskmap {

PoseGraphOptimizerOptions ReadPoseGraphOptimizerOptions(JsonFields& f) {
  PoseGraphOptimizerOptions o;
  f.Read("max_iterations", &o.max_iterations);
  f.Read("function_tolerance", &o.function_tolerance);
  std::string loss = "none";
  f.Read("robust_loss", &loss);
  if (loss == "none") {
    o.robust_loss = RobustLoss::kNone;
  } else if (loss == "huber") {
    o.robust_loss = RobustLoss::kHuber;
  } else if (loss == "cauchy") {
    o.robust_loss = RobustLoss::kCauchy;
  } else {
    SLAM_THROW(ConfigError) << f.where() << ".robust_loss: expected none, huber or cauchy, got '"
                            << loss << "'";
  }
  f.Read("robust_loss_scale", &o.robust_loss_scale);
  f.Read("max_error_ratio", &o.max_error_ratio);
  f.Read("initialize_from_links", &o.initialize_from_links);
  f.Read("num_threads", &o.num_threads);
  f.RejectUnknown();
  o.Check();
  return o;
}

}  // namespace duskmap
