#include "slam/retrieval/bayes_filter.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <utility>
#include <vector>

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

// A dense transition matrix built from the graph's neighbourhoods (spec §4.2
// steps 1-3), for comparing the filter's compact columns with.
std::vector<std::vector<double>> DenseTransitions(const PlaceGraph& g,
                                                  const std::vector<NodeId>& places) {
  const std::vector<double> c = BayesFilterOptions().prediction;
  const double sum_c = std::accumulate(c.begin(), c.end(), 0.0);
  const double eps = *std::min_element(c.begin(), c.end());
  const int max_margin = static_cast<int>(c.size()) - 2;
  std::map<NodeId, size_t> index;
  for (size_t k = 0; k < places.size(); ++k) index[places[k]] = k;
  // column[j][i] = P(i | j)
  std::vector<std::vector<double>> column(places.size(), std::vector<double>(places.size(), 0.0));
  for (size_t j = 0; j < places.size(); ++j) {
    double sum = 0.0;
    for (const NodeMargin& m : g.Neighbourhood(places[j])) {
      if (m.margin > max_margin || index.count(m.node) == 0) continue;
      column[j][index[m.node]] += c[m.margin + 1];
      sum += c[m.margin + 1];
    }
    if (sum < sum_c - c[0]) {
      column[j][j] += sum_c - c[0] - sum;
      sum = sum_c - c[0];
    }
    if (std::abs(sum - (1.0 - c[0])) > 1e-4) {
      for (double& w : column[j]) {
        w *= (1.0 - c[0]) / sum;
        if (w < eps) w = 0.0;
      }
    }
  }
  return column;
}

// Hundreds of places with slot gaps (places removed) and loop closures between
// sessions, so that columns hold hundreds of places and slot steps above 127:
// the compact columns give the dense model's posterior.
TEST(BayesFilter, CompactColumnsGiveTheDenseModelsPosterior) {
  constexpr NodeId kPerSession = 150;
  PlaceGraph g(16);
  for (NodeId n = 1; n <= 3 * kPerSession; ++n) {
    g.AddNode(n, static_cast<int>((n - 1) / kPerSession));
  }
  for (NodeId n = 1; n < 3 * kPerSession; ++n) {
    if (n % kPerSession != 0) g.AddLink(n, n + 1, LinkType::kOdometry);
  }
  for (NodeId n = 1; n <= kPerSession; n += 7) {
    g.AddLink(n, n + kPerSession, LinkType::kLoopClosure);
    g.AddLink(n + kPerSession, std::min<NodeId>(n + 2 * kPerSession + 3, 3 * kPerSession),
              LinkType::kLoopClosure);
  }
  BayesFilter f(BayesFilterOptions(), &g);
  for (NodeId n = 1; n <= 3 * kPerSession; ++n) f.AddPlace(n);
  for (NodeId n = 40; n <= 3 * kPerSession; n += 37) ASSERT_TRUE(f.RemovePlace(n));
  const std::vector<NodeId> places = f.Places();
  const std::vector<std::vector<double>> column = DenseTransitions(g, places);
  // A place's slot is its node id - 1 (added in order, none reused). Some
  // column must hold two places of one weight with no place of that weight
  // between them more than 127 slots apart: a step of two varint bytes.
  NodeId widest_step = 0;
  for (const auto& col : column) {
    std::map<double, std::vector<NodeId>> by_weight;
    for (size_t i = 0; i < col.size(); ++i) {
      if (col[i] > 0) by_weight[col[i]].push_back(places[i]);
    }
    for (const auto& [w, nodes] : by_weight) {
      for (size_t k = 1; k < nodes.size(); ++k) {
        widest_step = std::max(widest_step, nodes[k] - nodes[k - 1]);
      }
    }
  }
  ASSERT_GT(widest_step, 127);

  const BayesFilterOptions options;
  std::vector<double> posterior(places.size(), 1.0);
  double virtual_posterior = 1.0;
  const std::vector<std::pair<NodeId, float>> evidence = {{3, 4.0f}, {160, 2.5f}, {301, 6.0f}};
  for (const auto& [node, value] : evidence) {
    const Likelihood likelihood = Peak(node, value, 1.3f);
    f.Update(likelihood);
    // The same step, dense (spec §4.3).
    const double real_mass = std::accumulate(posterior.begin(), posterior.end(), 0.0);
    const double prior_virtual = options.virtual_place_prior * virtual_posterior +
                                 options.prediction[0] * real_mass;
    const double from_virtual =
        (1.0 - options.virtual_place_prior) / places.size() * virtual_posterior;
    std::vector<double> prior(places.size(), from_virtual);
    for (size_t j = 0; j < places.size(); ++j) {
      for (size_t i = 0; i < places.size(); ++i) prior[i] += column[j][i] * posterior[j];
    }
    for (size_t i = 0; i < places.size(); ++i) {
      if (places[i] == node) prior[i] *= value;
    }
    double total = prior_virtual * likelihood.virtual_place;
    for (double p : prior) total += p;
    for (size_t i = 0; i < places.size(); ++i) posterior[i] = prior[i] / total;
    virtual_posterior = prior_virtual * likelihood.virtual_place / total;

    // Columns keep float weights; a place's mass is about 2e-3, so a slot
    // decoded wrong would be off by far more than this.
    EXPECT_NEAR(f.VirtualPosterior(), virtual_posterior, 1e-7);
    for (size_t i = 0; i < places.size(); ++i) {
      ASSERT_NEAR(f.Posterior(places[i]), posterior[i], 1e-7) << "place " << places[i];
    }
  }
  // Less than half the bytes of one (slot, float weight) pair per entry, as
  // columns were kept before, even with these short columns' fixed costs.
  size_t entries = 0;
  for (const auto& col : column) {
    entries += std::count_if(col.begin(), col.end(), [](double w) { return w > 0; });
  }
  EXPECT_LT(f.TransitionBytes(), entries * (sizeof(uint32_t) + sizeof(float)) / 2);
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
