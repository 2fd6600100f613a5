// Discrete Bayes filter over the places of the map plus the virtual "new
// place" (reference: corelib/src/BayesFilter.cpp, spec §4).
//
// The transition model is sparse: each place keeps one column (the places it
// can move to, within max margin in the PlaceGraph, with their weights),
// cached until its neighbourhood or the set of places around it changes. The
// virtual place's column is uniform and never stored. Memory is about
// places x neighbourhood bytes instead of the reference's dense 4·n².
#pragma once

#include <cstdint>
#include <unordered_map>
#include <utility>
#include <vector>

#include "slam/core/graph_types.h"
#include "slam/retrieval/likelihood.h"
#include "slam/retrieval/place_graph.h"

namespace duskmap {

struct BayesFilterOptions {
  // Bayes/PredictionLC: [0] to the virtual place, [m + 1] to a neighbour at margin m.
  std::vector<double> prediction = {0.1,     0.36,    0.30,    0.16,    0.062,   0.0151,
                                    0.00255, 0.000324, 2.5e-05, 1.3e-06, 4.8e-08, 1.2e-09,
                                    1.9e-11, 2.2e-13, 1.7e-15, 8.5e-18, 2.9e-20, 6.9e-23};
  double virtual_place_prior = 0.9;  // Bayes/VirtualPlacePriorThr: P(virtual -> virtual)

  void Check() const;
  // Largest graph margin with a weight (16 with the default 18 values).
  int MaxMargin() const { return static_cast<int>(prediction.size()) - 2; }
};

// One place's posterior.
struct PlaceProbability {
  NodeId node = 0;
  double probability = 0.0;
};

class BayesFilter {
 public:
  // `graph` must outlive the filter and contain every place added.
  BayesFilter(const BayesFilterOptions& options, const PlaceGraph* graph);

  // A place enters the state (the reference: a node moving from STM to WM).
  // Throws InputError if the graph does not know it; no-op if present.
  void AddPlace(NodeId node);
  // False when absent.
  bool RemovePlace(NodeId node);
  bool ContainsPlace(NodeId node) const { return slot_of_.count(node) != 0; }
  size_t num_places() const { return slot_of_.size(); }
  std::vector<NodeId> Places() const;  // sorted

  // Forgets the posterior: the next update starts from all ones (§4.3).
  void Reset();
  // Prediction then update with `likelihood` (adjusted values; places not
  // listed have likelihood 1). Requires likelihood.computed.
  void Update(const Likelihood& likelihood);

  double VirtualPosterior() const { return virtual_posterior_; }
  double Posterior(NodeId node) const;
  // The k most probable real places, highest first (ties: smaller id first).
  std::vector<PlaceProbability> Top(int k) const;
  // Bytes of the cached transition columns (for the memory figures).
  size_t TransitionBytes() const;
  int columns_rebuilt_last_update() const { return columns_rebuilt_; }

 private:
  // A place's column: the places it moves to, in groups of one weight
  // (itself, then each graph margin), each group's slots increasing and
  // stored as LEB128 deltas: about a byte per place where a (slot, weight)
  // pair took eight. A map whose loop closures join every session puts most
  // of its places within a column's 16 links (the 48-session lifelong map:
  // about 770 of 1,002).
  struct Column {
    std::vector<uint8_t> slot_deltas;
    std::vector<std::pair<uint32_t, float>> groups;  // (places, P[place][this])
    uint64_t graph_version = 0;
    bool valid = false;
  };
  void BuildColumn(uint32_t slot);
  void InvalidateAround(NodeId node);
  void Predict(std::vector<double>* prior) const;

  BayesFilterOptions options_;
  const PlaceGraph* graph_;
  double sum_weights_ = 0.0;  // sum of options_.prediction
  std::unordered_map<NodeId, uint32_t> slot_of_;
  std::vector<NodeId> node_of_;     // slot -> node (0 when free)
  std::vector<uint32_t> free_slots_;
  std::vector<Column> columns_;     // by slot
  std::vector<std::vector<uint32_t>> by_margin_;  // BuildColumn's scratch
  std::vector<double> posterior_;   // by slot
  double virtual_posterior_ = 1.0;
  bool has_posterior_ = false;
  int columns_rebuilt_ = 0;
  bool any_column_built_ = false;  // once true, new places invalidate their neighbours
};

}  // namespace duskmap
