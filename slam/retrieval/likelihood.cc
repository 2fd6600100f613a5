#include "slam/retrieval/likelihood.h"

#include <algorithm>
#include <cmath>

#include "slam/core/check.h"

namespace duskmap {

float Likelihood::Raw(NodeId node) const {
  auto it = raw.find(node);
  return it == raw.end() ? 0.0f : it->second;
}

float Likelihood::Adjusted(NodeId node) const {
  if (!computed) return 0.0f;
  auto it = adjusted.find(node);
  return it == adjusted.end() ? 1.0f : it->second;
}

Likelihood ComputeLikelihood(const InvertedIndex& index, const std::vector<WordId>& query_words,
                             bool query_in_index,
                             const std::function<bool(NodeId)>& is_candidate, int num_candidates) {
  Likelihood out;
  out.computed = true;
  out.num_candidates = num_candidates;
  const int extra = query_in_index ? 0 : 1;
  const double num_nodes = static_cast<double>(index.num_nodes() + extra);
  for (WordId w : query_words) {
    const ReferenceList& refs = index.References(w);
    const int nodes_with_word = static_cast<int>(refs.size()) + extra;
    if (nodes_with_word == 0) continue;
    const double idf = std::log10(num_nodes / nodes_with_word);
    if (idf <= 0.0) continue;
    for (const WordReference& r : refs) {
      if (!is_candidate(r.node)) continue;
      out.raw[r.node] += static_cast<float>(r.count * idf * r.inverse_node_features);
    }
  }
  AdjustLikelihood(&out);
  return out;
}

void AdjustLikelihood(Likelihood* l) {
  constexpr double kEpsilon = 1e-4;
  l->adjusted.clear();
  double sum = 0.0, sum_sq = 0.0, max = 0.0;
  int count = 0;
  for (const auto& [node, value] : l->raw) {
    if (value <= 0.0f) continue;
    sum += value;
    sum_sq += static_cast<double>(value) * value;
    max = std::max<double>(max, value);
    ++count;
  }
  const double mean = count > 0 ? sum / count : 0.0;
  const double stddev = count > 0 ? std::sqrt(std::max(0.0, sum_sq / count - mean * mean)) : 0.0;
  l->mean = static_cast<float>(mean);
  l->stddev = static_cast<float>(stddev);
  l->max = static_cast<float>(max);
  if (mean > 0.0) {
    for (const auto& [node, value] : l->raw) {
      if (value > mean + stddev) {
        l->adjusted[node] = static_cast<float>((value - (stddev - kEpsilon)) / mean);
      }
    }
  }
  l->virtual_place = (stddev > kEpsilon && max > 0.0) ? static_cast<float>(mean / stddev + 1.0)
                                                      : 2.0f;
}

}  // namespace duskmap
