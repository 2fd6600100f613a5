#include "slam/eval/gap_metrics.h"

#include <gtest/gtest.h>

#include "slam/core/check.h"

namespace duskmap {
namespace {

// Frames 0.5 m apart along x.
std::vector<Eigen::Vector3d> Line(int n) {
  std::vector<Eigen::Vector3d> p;
  for (int i = 0; i < n; ++i) p.emplace_back(0.5 * i, 0, 0);
  return p;
}

TEST(ComputeGapMetrics, LargestGapAndWithinShare) {
  //                 0     1     2      3      4      5     6      7
  std::vector<bool> r = {true, true, false, false, false, true, true, false};
  const GapMetrics m = ComputeGapMetrics(Line(8), r);
  EXPECT_DOUBLE_EQ(m.total_distance_m, 3.5);
  EXPECT_DOUBLE_EQ(m.max_gap_m, 2.0);  // frame 1 -> frame 5
  EXPECT_EQ(m.num_relocalized, 4);
  EXPECT_EQ(m.num_within, 3);  // frames 0, 1, 6 (frame 5 came 2 m after frame 1)
  EXPECT_DOUBLE_EQ(m.within_pct, 100.0 * 3 / 8);
  EXPECT_DOUBLE_EQ(m.distance_since_last_m[4], 1.5);
  EXPECT_DOUBLE_EQ(m.distance_since_last_m[5], 0.0);
  EXPECT_DOUBLE_EQ(m.distance_since_last_m[7], 0.5);
}

TEST(ComputeGapMetrics, NeverRelocalizedGapIsWholePath) {
  const GapMetrics m = ComputeGapMetrics(Line(5), std::vector<bool>(5, false));
  EXPECT_DOUBLE_EQ(m.max_gap_m, 2.0);
  EXPECT_EQ(m.num_within, 0);
}

TEST(ComputeGapMetrics, RejectsBadInput) {
  EXPECT_THROW(ComputeGapMetrics(Line(3), {true}), InputError);
  GapMetricsOptions bad;
  bad.within_m = 0.0;
  EXPECT_THROW(ComputeGapMetrics(Line(3), {true, true, true}, bad), ConfigError);
}

}  // namespace
}  // namespace duskmap
