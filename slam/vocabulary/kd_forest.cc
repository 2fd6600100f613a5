#include "slam/vocabulary/kd_forest.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>

#include "slam/core/check.h"

namespace duskmap {
namespace {

constexpr int kSampleRows = 100;  // rows sampled for the split statistics (FLANN: SAMPLE_MEAN)
constexpr int kTopDims = 5;       // split among the 5 most varying dimensions (FLANN: RAND_DIM)

bool Closer(const KdNeighbour& a, const KdNeighbour& b) {
  return a.distance < b.distance || (a.distance == b.distance && a.id < b.id);
}

}  // namespace

KdForest::KdForest(const KdForestOptions& options, DescriptorKind kind, int cols)
    : options_(options), kind_(kind), cols_(cols),
      dims_(kind == DescriptorKind::kFloat ? cols : cols * 8),
      row_bytes_(kind == DescriptorKind::kFloat ? cols * sizeof(float) : cols),
      rng_(options.seed) {
  SLAM_CHECK(options.trees >= 1 && options.checks >= 1 && options.leaf_size >= 1);
  SLAM_CHECK(options.rebuild_factor > 1.0 && cols > 0);
}

float KdForest::QueryValue(const uint8_t* q, int dim) const {
  if (kind_ == DescriptorKind::kFloat) return reinterpret_cast<const float*>(q)[dim];
  return static_cast<float>((q[dim >> 3] >> (dim & 7)) & 1);
}

float KdForest::Value(uint32_t p, int dim) const { return QueryValue(Data(p), dim); }

float KdForest::Distance(const uint8_t* q, uint32_t p) const {
  return DescriptorDistance(kind_, q, Data(p), cols_);
}

const uint8_t* KdForest::Row(WordId id) const {
  auto it = slot_.find(id);
  SLAM_CHECK(it != slot_.end());
  return Data(it->second);
}

int32_t KdForest::MakeLeaf(const std::vector<uint32_t>& idx, size_t begin, size_t end) {
  Node node;
  node.leaf = static_cast<int32_t>(leaves_.size());
  leaves_.emplace_back(idx.begin() + begin, idx.begin() + end);
  nodes_.push_back(node);
  return static_cast<int32_t>(nodes_.size() - 1);
}

// Splits rows idx[begin, end) at the mean of one of the most varying
// dimensions (estimated on up to kSampleRows rows), chosen at random.
int32_t KdForest::Divide(std::vector<uint32_t>* idx, size_t begin, size_t end) {
  const size_t count = end - begin;
  if (count <= static_cast<size_t>(options_.leaf_size)) return MakeLeaf(*idx, begin, end);
  const size_t sample = std::min<size_t>(count, kSampleRows);
  std::vector<double> mean(dims_, 0.0), var(dims_, 0.0);
  for (size_t i = 0; i < sample; ++i) {
    const uint32_t p = (*idx)[begin + i];
    for (int d = 0; d < dims_; ++d) mean[d] += Value(p, d);
  }
  for (double& m : mean) m /= sample;
  for (size_t i = 0; i < sample; ++i) {
    const uint32_t p = (*idx)[begin + i];
    for (int d = 0; d < dims_; ++d) {
      const double diff = Value(p, d) - mean[d];
      var[d] += diff * diff;
    }
  }
  std::vector<int> order(dims_);
  std::iota(order.begin(), order.end(), 0);
  const int top = std::min(kTopDims, dims_);
  std::partial_sort(order.begin(), order.begin() + top, order.end(),
                    [&](int a, int b) { return var[a] != var[b] ? var[a] > var[b] : a < b; });
  int usable = 0;
  while (usable < top && var[order[usable]] > 0.0) ++usable;
  if (usable == 0) return MakeLeaf(*idx, begin, end);  // identical rows
  const int dim = order[std::uniform_int_distribution<int>(0, usable - 1)(rng_)];
  const float split = static_cast<float>(mean[dim]);
  auto middle = std::partition(idx->begin() + begin, idx->begin() + end,
                               [&](uint32_t p) { return Value(p, dim) < split; });
  const size_t mid = static_cast<size_t>(middle - idx->begin());
  if (mid == begin || mid == end) return MakeLeaf(*idx, begin, end);
  Node node;
  node.dim = dim;
  node.split = split;
  nodes_.push_back(node);
  const int32_t self = static_cast<int32_t>(nodes_.size() - 1);
  const int32_t left = Divide(idx, begin, mid);
  const int32_t right = Divide(idx, mid, end);
  nodes_[self].child[0] = left;
  nodes_[self].child[1] = right;
  return self;
}

void KdForest::Rebuild() {
  std::vector<uint8_t> data;
  std::vector<WordId> ids;
  data.reserve(slot_.size() * row_bytes_);
  ids.reserve(slot_.size());
  for (uint32_t p = 0; p < ids_.size(); ++p) {
    if (ids_[p] == kNoWord) continue;
    slot_[ids_[p]] = static_cast<uint32_t>(ids.size());
    ids.push_back(ids_[p]);
    data.insert(data.end(), Data(p), Data(p) + row_bytes_);
  }
  data_.swap(data);
  ids_.swap(ids);
  nodes_.clear();
  leaves_.clear();
  roots_.clear();
  rows_at_build_ = ids_.size();
  ++rebuilds_;
  if (ids_.empty()) return;
  std::vector<uint32_t> idx(ids_.size());
  for (int t = 0; t < options_.trees; ++t) {
    std::iota(idx.begin(), idx.end(), 0u);
    std::shuffle(idx.begin(), idx.end(), rng_);
    roots_.push_back(Divide(&idx, 0, idx.size()));
  }
}

void KdForest::Insert(int tree, uint32_t p) {
  int32_t n = roots_[tree];
  while (nodes_[n].dim >= 0) n = nodes_[n].child[Value(p, nodes_[n].dim) < nodes_[n].split ? 0 : 1];
  std::vector<uint32_t>& leaf = leaves_[nodes_[n].leaf];
  leaf.push_back(p);
  if (leaf.size() <= static_cast<size_t>(options_.leaf_size)) return;
  std::vector<uint32_t> points = leaf;
  const int32_t sub = Divide(&points, 0, points.size());
  if (nodes_[sub].dim < 0) return;  // rows identical on every sampled dimension: keep the leaf
  leaves_[nodes_[n].leaf] = std::vector<uint32_t>();
  nodes_[n] = nodes_[sub];  // the subtree's root slot is left unused until the next rebuild
}

void KdForest::Add(WordId id, const uint8_t* row) {
  SLAM_CHECK(id > 0 && !Contains(id));
  const uint32_t p = static_cast<uint32_t>(ids_.size());
  data_.insert(data_.end(), row, row + row_bytes_);
  ids_.push_back(id);
  slot_[id] = p;
  if (roots_.empty() || ids_.size() > rows_at_build_ * options_.rebuild_factor) {
    Rebuild();
    return;
  }
  for (int t = 0; t < options_.trees; ++t) Insert(t, p);
}

bool KdForest::Remove(WordId id) {
  auto it = slot_.find(id);
  if (it == slot_.end()) return false;
  ids_[it->second] = kNoWord;
  slot_.erase(it);
  if (slot_.empty()) Rebuild();  // frees everything
  return true;
}

void KdForest::Descend(int32_t n, const uint8_t* q, float mindist, int* checks,
                       std::vector<std::pair<float, int32_t>>* heap, KdNeighbour best[2],
                       int* found) const {
  while (nodes_[n].dim >= 0) {
    const Node& node = nodes_[n];
    const float diff = QueryValue(q, node.dim) - node.split;
    const int near = diff < 0 ? 0 : 1;
    const float far = mindist + (kind_ == DescriptorKind::kFloat ? diff * diff : std::abs(diff));
    heap->push_back({far, node.child[1 - near]});
    std::push_heap(heap->begin(), heap->end(), std::greater<>());
    n = node.child[near];
  }
  for (uint32_t p : leaves_[nodes_[n].leaf]) {
    if (ids_[p] == kNoWord || visited_[p] == stamp_) continue;
    visited_[p] = stamp_;
    ++*checks;
    const KdNeighbour c{ids_[p], Distance(q, p)};
    if (*found < 2) {
      best[(*found)++] = c;
      if (*found == 2 && Closer(best[1], best[0])) std::swap(best[0], best[1]);
    } else if (Closer(c, best[1])) {
      best[1] = c;
      if (Closer(best[1], best[0])) std::swap(best[0], best[1]);
    }
  }
}

void KdForest::SearchTwo(const uint8_t* query, std::vector<KdNeighbour>* out) const {
  out->clear();
  if (slot_.empty()) return;
  if (visited_.size() < ids_.size()) visited_.resize(ids_.size(), 0);
  if (++stamp_ == 0) {
    std::fill(visited_.begin(), visited_.end(), 0);
    stamp_ = 1;
  }
  KdNeighbour best[2];
  int found = 0, checks = 0;
  std::vector<std::pair<float, int32_t>>& heap = heap_;
  heap.clear();
  for (int32_t root : roots_) Descend(root, query, 0.0f, &checks, &heap, best, &found);
  while (!heap.empty() && (checks < options_.checks || found < 2)) {
    std::pop_heap(heap.begin(), heap.end(), std::greater<>());
    const auto [mindist, node] = heap.back();
    heap.pop_back();
    Descend(node, query, mindist, &checks, &heap, best, &found);
  }
  out->assign(best, best + found);
}

size_t KdForest::MemoryBytes() const {
  size_t bytes = data_.capacity() + ids_.capacity() * sizeof(WordId) +
                 visited_.capacity() * sizeof(uint32_t) + nodes_.capacity() * sizeof(Node) +
                 leaves_.capacity() * sizeof(leaves_[0]);
  for (const auto& leaf : leaves_) bytes += leaf.capacity() * sizeof(uint32_t);
  // unordered_map: one heap node (next pointer, key, value, cached hash) per id plus buckets.
  bytes += slot_.size() * 24 + slot_.bucket_count() * sizeof(void*);
  return bytes;
}

}  // namespace duskmap
