#include "slam/retrieval/bayes_filter.h"

#include <numeric>

#include <gtest/gtest.h>

#include "slam/core/check.h"

namespace duskmap {
namespace {

PlaceGraph Chain(int n) {
  PlaceGraph g(16);
  for (NodeId i = 1; i <= n; ++i) g.AddNode(i, 0);
  for (NodeId i = 1; i < n; ++i) g.AddLink(i, i + 1, LinkType::kOdometry);
  return g;
}

Likelihood Flat() {
  Likelihood l;
  l.computed = true;
  l.virtual_place = 2.0f;
  return l;
}

Likelihood Peak(NodeId node, float value, float virtual_place) {
  Likelihood l = Flat();
  l.adjusted[node] = value;
  l.virtual_place = virtual_place;
  return l;
}

double Total(const BayesFilter& f) {
  double total = f.VirtualPosterior();
  for (NodeId n : f.Places()) total += f.Posterior(n);
  return total;
}

TEST(BayesFilter, FirstUpdateMatchesADenseComputation) {
  PlaceGraph g = Chain(3);
  BayesFilter f(BayesFilterOptions(), &g);
  for (NodeId n = 1; n <= 3; ++n) f.AddPlace(n);
  f.Update(Peak(2, 3.0f, 1.5f));
  // Dense reference (spec §4.2-4.3) with posterior_old = 1 everywhere.
  const std::vector<double> c = BayesFilterOptions().prediction;
  const double sum_c = std::accumulate(c.begin(), c.end(), 0.0);
  // Columns: node 1 -> {1: c1 + missing, 2: c2, 3: c3};
  // node 2 -> {1: c2, 2: c1, 3: c2} = 0.96 > 1 - c0: rescaled to 1 - c0;
  // node 3 mirrors node 1.
  const double col1_self = c[1] + (sum_c - c[0] - (c[1] + c[2] + c[3]));
  const double scale2 = (1.0 - c[0]) / (c[1] + 2 * c[2]);
  const double col2_self = c[1] * scale2;
  const double u = 0.1 / 3.0;
  const double prior_v = 0.9 + 3 * c[0];
  const double prior1 = u + col1_self + c[2] * scale2 + c[3];
  const double prior2 = u + c[2] + col2_self + c[2];
  const double prior3 = prior1;
  const double post_v = prior_v * 1.5, post1 = prior1, post2 = prior2 * 3.0, post3 = prior3;
  const double total = post_v + post1 + post2 + post3;
  EXPECT_NEAR(f.VirtualPosterior(), post_v / total, 1e-6);
  EXPECT_NEAR(f.Posterior(1), post1 / total, 1e-6);
  EXPECT_NEAR(f.Posterior(2), post2 / total, 1e-6);
  EXPECT_NEAR(Total(f), 1.0, 1e-9);
  EXPECT_EQ(f.Top(1)[0].node, 2);
}

TEST(BayesFilter, RepeatedEvidenceAccumulatesAndNeighboursShareIt) {
  PlaceGraph g = Chain(30);
  BayesFilter f(BayesFilterOptions(), &g);
  for (NodeId n = 1; n <= 30; ++n) f.AddPlace(n);
  for (int i = 0; i < 10; ++i) f.Update(Flat());
  const double flat_virtual = f.VirtualPosterior();
  EXPECT_GT(flat_virtual, 0.5);  // no evidence: the new place dominates
  f.Update(Peak(15, 4.0f, 1.2f));
  const double once = 1.0 - f.VirtualPosterior();
  f.Update(Peak(16, 4.0f, 1.2f));
  EXPECT_GT(1.0 - f.VirtualPosterior(), once);
  EXPECT_GT(f.Posterior(15), f.Posterior(25));  // neighbours of the evidence gain
  EXPECT_NEAR(Total(f), 1.0, 1e-9);
}

TEST(BayesFilter, LoopClosureEquivalentsGetTheSameMass) {
  PlaceGraph g = Chain(10);
  for (NodeId n = 11; n <= 20; ++n) g.AddNode(n, 1);
  for (NodeId n = 11; n < 20; ++n) g.AddLink(n, n + 1, LinkType::kOdometry);
  g.AddLink(5, 15, LinkType::kLoopClosure);
  BayesFilter f(BayesFilterOptions(), &g);
  for (NodeId n = 1; n <= 20; ++n) f.AddPlace(n);
  f.Update(Flat());
  f.Update(Peak(5, 5.0f, 1.1f));
  f.Update(Flat());
  EXPECT_GT(f.Posterior(15), f.Posterior(12));  // the other session's same place gained
  EXPECT_NEAR(Total(f), 1.0, 1e-9);
}

TEST(BayesFilter, PlacesComeAndGoAndResetRestarts) {
  PlaceGraph g = Chain(5);
  BayesFilter f(BayesFilterOptions(), &g);
  f.Update(Flat());  // no place: the new place is certain
  EXPECT_EQ(f.VirtualPosterior(), 1.0);
  f.AddPlace(1);
  f.AddPlace(2);
  f.Update(Peak(2, 3.0f, 1.5f));
  f.AddPlace(3);
  EXPECT_EQ(f.Posterior(3), 0.0);  // new places start empty
  f.Update(Flat());
  EXPECT_GT(f.Posterior(3), 0.0);
  EXPECT_TRUE(f.RemovePlace(2));
  EXPECT_FALSE(f.RemovePlace(2));
  f.Update(Flat());
  EXPECT_NEAR(Total(f), 1.0, 1e-9);
  f.Reset();
  f.Update(Flat());
  EXPECT_NEAR(Total(f), 1.0, 1e-9);
  EXPECT_THROW(f.AddPlace(77), InputError);
  BayesFilterOptions bad;
  bad.prediction = {0.5};
  EXPECT_THROW(bad.Check(), ConfigError);
}

}  // namespace
}  // namespace duskmap
