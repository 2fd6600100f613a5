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
  EXPECT_EQ(m.num_within_bound, 8);  // every step is 0.5 m
}

TEST(ComputeGapMetrics, BoundCountsOnlyStepsUpToWithin) {
  // Steps 0.5, 0.6, 0.55, 0.3 m: the 0.6 m step cannot count even when both
  // of its frames re-localize; 0.55 m (== within_m) can.
  const std::vector<Eigen::Vector3d> p = {
      {0, 0, 0}, {0.5, 0, 0}, {1.1, 0, 0}, {1.65, 0, 0}, {1.95, 0, 0}};
  const GapMetrics all = ComputeGapMetrics(p, std::vector<bool>(5, true));
  EXPECT_EQ(all.num_within_bound, 4);
  EXPECT_EQ(all.num_within, all.num_within_bound);  // every frame re-localized: the bound is met
  // The bound is the path's alone: re-localizing less does not change it.
  const GapMetrics some = ComputeGapMetrics(p, {true, false, true, false, true});
  EXPECT_EQ(some.num_within_bound, 4);
  EXPECT_EQ(some.num_within, 1);  // frame 0 only (frames 2 and 4 came 1.1 and 0.85 m later)
}

TEST(ComputeGapMetrics, NeverRelocalizedGapIsWholePath) {
  const GapMetrics m = ComputeGapMetrics(Line(5), std::vector<bool>(5, false));
  EXPECT_DOUBLE_EQ(m.max_gap_m, 2.0);
  EXPECT_EQ(m.num_within, 0);
  EXPECT_EQ(m.num_within_bound, 5);
}

TEST(ComputeGapMetrics, RejectsBadInput) {
  EXPECT_THROW(ComputeGapMetrics(Line(3), {true}), InputError);
  GapMetricsOptions bad;
  bad.within_m = 0.0;
  EXPECT_THROW(ComputeGapMetrics(Line(3), {true, true, true}, bad), ConfigError);
}

}  // namespace
}  // namespace duskmap
