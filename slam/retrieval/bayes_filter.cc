#include "slam/retrieval/bayes_filter.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "slam/core/check.h"

namespace duskmap {

void BayesFilterOptions::Check() const {
  SLAM_THROW_IF_NOT(ConfigError, prediction.size() >= 2)
      << "BayesFilterOptions.prediction needs >= 2 values, got " << prediction.size();
  for (double c : prediction) {
    SLAM_THROW_IF_NOT(ConfigError, c >= 0.0 && c <= 1.0)
        << "BayesFilterOptions.prediction values must be in [0, 1], got " << c;
  }
  SLAM_THROW_IF_NOT(ConfigError, prediction[0] < 1.0)
      << "BayesFilterOptions.prediction[0] must be < 1, got " << prediction[0];
  SLAM_THROW_IF_NOT(ConfigError, virtual_place_prior >= 0.0 && virtual_place_prior <= 1.0)
      << "BayesFilterOptions.virtual_place_prior must be in [0, 1], got " << virtual_place_prior;
}

BayesFilter::BayesFilter(const BayesFilterOptions& options, const PlaceGraph* graph)
    : options_(options), graph_(graph) {
  options_.Check();
  SLAM_CHECK(graph_ != nullptr);
  sum_weights_ = std::accumulate(options_.prediction.begin(), options_.prediction.end(), 0.0);
}

void BayesFilter::AddPlace(NodeId node) {
  SLAM_THROW_IF_NOT(InputError, graph_->Contains(node))
      << "BayesFilter: place " << node << " is not in the place graph";
  if (ContainsPlace(node)) return;
  uint32_t slot;
  if (!free_slots_.empty()) {
    slot = free_slots_.back();
    free_slots_.pop_back();
  } else {
    slot = static_cast<uint32_t>(node_of_.size());
    node_of_.push_back(0);
    columns_.emplace_back();
    posterior_.push_back(0.0);
  }
  node_of_[slot] = node;
  posterior_[slot] = 0.0;  // a new place starts with no mass (§4.3)
  columns_[slot] = Column();
  slot_of_.emplace(node, slot);
  // Before the first column is built every column is invalid anyway (a map's
  // places being imported): no neighbourhood needs to be searched.
  if (any_column_built_) InvalidateAround(node);
}

bool BayesFilter::RemovePlace(NodeId node) {
  auto it = slot_of_.find(node);
  if (it == slot_of_.end()) return false;
  const uint32_t slot = it->second;
  // If the graph already dropped the node, it bumped the neighbours' versions.
  if (graph_->Contains(node)) InvalidateAround(node);
  slot_of_.erase(it);
  node_of_[slot] = 0;
  posterior_[slot] = 0.0;
  columns_[slot] = Column();
  free_slots_.push_back(slot);
  return true;
}

std::vector<NodeId> BayesFilter::Places() const {
  std::vector<NodeId> out;
  out.reserve(slot_of_.size());
  for (const auto& [node, slot] : slot_of_) out.push_back(node);
  std::sort(out.begin(), out.end());
  return out;
}

void BayesFilter::Reset() {
  std::fill(posterior_.begin(), posterior_.end(), 0.0);
  virtual_posterior_ = 1.0;
  has_posterior_ = false;
}

void BayesFilter::InvalidateAround(NodeId node) {
  for (const NodeMargin& m : graph_->Neighbourhood(node)) {
    auto it = slot_of_.find(m.node);
    if (it != slot_of_.end()) columns_[it->second].valid = false;
  }
}

namespace {

void AppendVarint(uint32_t value, std::vector<uint8_t>* out) {
  while (value >= 0x80) {
    out->push_back(static_cast<uint8_t>(value | 0x80));
    value >>= 7;
  }
  out->push_back(static_cast<uint8_t>(value));
}

uint32_t ReadVarint(const uint8_t** at) {
  uint32_t value = 0;
  for (int shift = 0;; shift += 7) {
    const uint8_t byte = *(*at)++;
    value |= static_cast<uint32_t>(byte & 0x7f) << shift;
    if (byte < 0x80) return value;
  }
}

}  // namespace

// Column of place j (spec §4.2 steps 1-3): weights by graph margin to the
// places in the state, missing mass on the diagonal, rescaled to 1 - c[0].
// Every place of one margin has the same weight, so the column stores groups
// (itself, then each margin) rather than one weight per place.
void BayesFilter::BuildColumn(uint32_t slot) {
  const std::vector<double>& c = options_.prediction;
  const NodeId node = node_of_[slot];
  const int max_margin = options_.MaxMargin();
  // by_margin_[0] holds the place itself, by_margin_[m + 1] the others at margin m.
  by_margin_.resize(static_cast<size_t>(max_margin) + 2);
  for (std::vector<uint32_t>& group : by_margin_) group.clear();
  double sum = 0.0;
  for (const NodeMargin& m : graph_->Neighbourhood(node)) {
    if (m.margin > max_margin) break;  // sorted by margin
    auto it = slot_of_.find(m.node);
    if (it == slot_of_.end()) continue;
    by_margin_[it->second == slot ? 0 : m.margin + 1].push_back(it->second);
    sum += c[m.margin + 1];
  }
  // Group g > 0 (margin g - 1) weighs c[g]; the place itself, margin 0, c[1].
  std::vector<float> weights(c.begin(), c.end());
  weights[0] = static_cast<float>(c[1]);
  const double target = 1.0 - c[0];
  if (sum < sum_weights_ - c[0]) {
    SLAM_CHECK(!by_margin_[0].empty());
    weights[0] += static_cast<float>(sum_weights_ - c[0] - sum);
    sum = sum_weights_ - c[0];
  }
  bool drop_small = false;
  if (std::abs(sum - target) > 1e-4) {
    const double scale = target / sum;
    for (float& w : weights) w = static_cast<float>(w * scale);
    drop_small = true;
  }
  const double eps = *std::min_element(c.begin(), c.end());
  Column column;
  for (size_t g = 0; g < by_margin_.size(); ++g) {
    std::vector<uint32_t>& group = by_margin_[g];
    if (group.empty() || (drop_small && weights[g] < eps)) continue;
    std::sort(group.begin(), group.end());
    uint32_t previous = 0;
    for (uint32_t s : group) {
      AppendVarint(s - previous, &column.slot_deltas);
      previous = s;
    }
    column.groups.push_back({static_cast<uint32_t>(group.size()), weights[g]});
  }
  column.slot_deltas.shrink_to_fit();
  column.groups.shrink_to_fit();
  column.graph_version = graph_->Version(node);
  column.valid = true;
  columns_[slot] = std::move(column);
  any_column_built_ = true;
}

void BayesFilter::Predict(std::vector<double>* prior) const {
  const size_t n = slot_of_.size();
  const double from_virtual = (1.0 - options_.virtual_place_prior) / n * virtual_posterior_;
  prior->assign(posterior_.size(), 0.0);
  for (const auto& [node, slot] : slot_of_) (*prior)[slot] = from_virtual;
  for (size_t j = 0; j < posterior_.size(); ++j) {
    const double p = posterior_[j];
    if (p == 0.0 || node_of_[j] == 0) continue;
    const uint8_t* at = columns_[j].slot_deltas.data();
    for (const auto& [count, w] : columns_[j].groups) {
      const double weighted = w * p;
      uint32_t i = 0;
      for (uint32_t k = 0; k < count; ++k) {
        i += ReadVarint(&at);
        (*prior)[i] += weighted;
      }
    }
  }
}

void BayesFilter::Update(const Likelihood& likelihood) {
  SLAM_CHECK(likelihood.computed);
  columns_rebuilt_ = 0;
  if (slot_of_.empty()) {
    virtual_posterior_ = 1.0;
    return;
  }
  if (!has_posterior_) {
    for (const auto& [node, slot] : slot_of_) posterior_[slot] = 1.0;
    virtual_posterior_ = 1.0;
    has_posterior_ = true;
  }
  for (const auto& [node, slot] : slot_of_) {
    Column& column = columns_[slot];
    if (!column.valid || column.graph_version != graph_->Version(node)) {
      BuildColumn(slot);
      ++columns_rebuilt_;
    }
  }
  double real_mass = 0.0;
  for (const auto& [node, slot] : slot_of_) real_mass += posterior_[slot];
  const double prior_virtual =
      options_.virtual_place_prior * virtual_posterior_ + options_.prediction[0] * real_mass;
  std::vector<double> prior;
  Predict(&prior);
  for (const auto& [node, value] : likelihood.adjusted) {
    auto it = slot_of_.find(node);
    if (it != slot_of_.end()) prior[it->second] *= value;
  }
  const double virtual_value = prior_virtual * likelihood.virtual_place;
  double total = virtual_value;
  for (const auto& [node, slot] : slot_of_) total += prior[slot];
  if (total <= 0.0) return;  // reference: normalisation skipped, keep the previous state
  posterior_.swap(prior);
  for (double& p : posterior_) p /= total;
  virtual_posterior_ = virtual_value / total;
}

double BayesFilter::Posterior(NodeId node) const {
  auto it = slot_of_.find(node);
  return it == slot_of_.end() ? 0.0 : posterior_[it->second];
}

std::vector<PlaceProbability> BayesFilter::Top(int k) const {
  std::vector<PlaceProbability> all;
  all.reserve(slot_of_.size());
  for (const auto& [node, slot] : slot_of_) all.push_back({node, posterior_[slot]});
  auto better = [](const PlaceProbability& a, const PlaceProbability& b) {
    return a.probability != b.probability ? a.probability > b.probability : a.node < b.node;
  };
  const size_t keep = std::min<size_t>(std::max(k, 0), all.size());
  std::partial_sort(all.begin(), all.begin() + keep, all.end(), better);
  all.resize(keep);
  return all;
}

size_t BayesFilter::TransitionBytes() const {
  size_t bytes = columns_.capacity() * sizeof(Column);
  for (const Column& c : columns_) {
    bytes += c.slot_deltas.capacity() + c.groups.capacity() * sizeof(c.groups[0]);
  }
  return bytes;
}

}  // namespace duskmap
