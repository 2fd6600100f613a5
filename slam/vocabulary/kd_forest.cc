#include "slam/vocabulary/kd_forest.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>

#include <new>

#ifdef __linux__
#include <sys/mman.h>
#endif

#include "slam/core/check.h"

namespace duskmap {
namespace {

constexpr int kSampleRows = 100;  // rows sampled for the split statistics (FLANN: SAMPLE_MEAN)
constexpr int kTopDims = 5;       // split among the 5 most varying dimensions (FLANN: RAND_DIM)

bool Closer(const KdNeighbour& a, const KdNeighbour& b) {
  return a.distance < b.distance || (a.distance == b.distance && a.id < b.id);
}

}  // namespace

void* AllocateHugePageAdvised(size_t bytes) {
  constexpr size_t kHugePage = size_t{2} << 20;
  if (bytes < 2 * kHugePage) {
    void* p = std::malloc(bytes == 0 ? 1 : bytes);
    if (p == nullptr) throw std::bad_alloc();
    return p;
  }
  const size_t rounded = (bytes + kHugePage - 1) / kHugePage * kHugePage;
  void* p = std::aligned_alloc(kHugePage, rounded);
  if (p == nullptr) throw std::bad_alloc();
#ifdef __linux__
  madvise(p, rounded, MADV_HUGEPAGE);  // advice only: failure leaves ordinary pages
#endif
  return p;
}

KdForest::KdForest(const KdForestOptions& options, WordRowFormat format, int cols)
    : options_(options), format_(format), cols_(cols),
      dims_(WordRowDims(format, cols, options.binary_distance)),
      row_bytes_(WordRowBytes(format, cols)),
      rng_(options.seed) {
  SLAM_CHECK(options.trees >= 1 && options.checks >= 1 && options.leaf_size >= 1);
  SLAM_CHECK(options.rebuild_factor > 1.0 && cols > 0);
}

float KdForest::QueryValue(const uint8_t* q, int dim) const {
  if (format_ != WordRowFormat::kBinary) return reinterpret_cast<const float*>(q)[dim];
  if (options_.binary_distance == BinaryDistance::kByteL1) return static_cast<float>(q[dim]);
  return static_cast<float>((q[dim >> 3] >> (dim & 7)) & 1);
}

float KdForest::Value(uint32_t p, int dim) const {
  return WordRowValue(format_, Data(p), dim, options_.binary_distance);
}

const uint8_t* KdForest::Row(WordId id) const {
  const uint32_t p = slot_.Find(id);
  SLAM_CHECK(p != WordSlots::kNone);
  return Data(p);
}

const uint32_t* KdForest::LeafPoints(const Node& leaf) const {
  // int32_t and uint32_t may alias; point indices are below 2^31.
  if (leaf.dim == kPointLeaf) return reinterpret_cast<const uint32_t*>(&leaf.child[0]);
  return &pool_[leaf.child[0]];
}

int32_t KdForest::AppendBlock(const uint32_t* points, int32_t count, uint32_t capacity) {
  pool_.push_back(capacity);
  const int32_t offset = static_cast<int32_t>(pool_.size());
  pool_.insert(pool_.end(), points, points + count);
  pool_.resize(pool_.size() + capacity - count);
  return offset;
}

int32_t KdForest::MakeLeaf(const std::vector<uint32_t>& idx, size_t begin, size_t end) {
  const size_t count = end - begin;
  Node node;
  node.child[1] = static_cast<int32_t>(count);
  if (count == 1) {
    node.dim = kPointLeaf;
    node.child[0] = static_cast<int32_t>(idx[begin]);
  } else {
    const size_t capacity = std::max(count, static_cast<size_t>(options_.leaf_size) + 1);
    node.child[0] = AppendBlock(&idx[begin], static_cast<int32_t>(count),
                                static_cast<uint32_t>(capacity));
  }
  nodes_.push_back(node);
  return static_cast<int32_t>(nodes_.size() - 1);
}

int32_t KdForest::LeafOf(int tree, uint32_t p) const {
  int32_t n = roots_[tree];
  while (nodes_[n].dim >= 0) n = nodes_[n].child[Value(p, nodes_[n].dim) < nodes_[n].split ? 0 : 1];
  return n;
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
  // Live points in id order: ids are added in increasing order, so this is
  // the insertion order, which fixes the shuffles below.
  std::vector<std::pair<WordId, uint32_t>> live;
  live.reserve(slot_.size());
  slot_.ForEach([&live](WordId id, uint32_t p) { live.push_back({id, p}); });
  if (live.empty()) slot_.Clear();
  std::vector<uint8_t, HugePageAllocator<uint8_t>> data;
  std::vector<WordId> ids;
  data.reserve(live.size() * row_bytes_);
  ids.reserve(live.size());
  for (const auto& [id, p] : live) {
    slot_.Set(id, static_cast<uint32_t>(ids.size()));
    ids.push_back(id);
    data.insert(data.end(), Data(p), Data(p) + row_bytes_);
  }
  data_.swap(data);
  ids_.swap(ids);
  nodes_.clear();
  pool_.clear();
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
  RenumberByLeaves();
  // The trees grew node by node; keep only what they use (a map loaded for
  // localization is built once and never grows).
  nodes_.shrink_to_fit();
  pool_.shrink_to_fit();
}

void KdForest::RenumberByLeaves() {
  const uint32_t n = static_cast<uint32_t>(ids_.size());
  constexpr uint32_t kUnset = ~0u;
  std::vector<uint32_t> renamed(n, kUnset);
  uint32_t next = 0;
  std::vector<int32_t> stack = {roots_[0]};
  while (!stack.empty()) {
    const Node node = nodes_[stack.back()];
    stack.pop_back();
    if (node.dim >= 0) {
      stack.push_back(node.child[1]);
      stack.push_back(node.child[0]);
      continue;
    }
    const uint32_t* points = LeafPoints(node);
    for (int32_t i = 0; i < node.child[1]; ++i) {
      uint32_t& r = renamed[points[i]];
      if (r == kUnset) r = next++;
    }
  }
  for (uint32_t& r : renamed) {
    if (r == kUnset) r = next++;  // not in the first tree (cannot happen after a build)
  }
  std::vector<uint8_t, HugePageAllocator<uint8_t>> data(data_.size());
  std::vector<WordId> ids(n);
  for (uint32_t p = 0; p < n; ++p) {
    std::copy_n(Data(p), row_bytes_, &data[static_cast<size_t>(renamed[p]) * row_bytes_]);
    ids[renamed[p]] = ids_[p];
    slot_.Set(ids_[p], renamed[p]);
  }
  data_.swap(data);
  ids_.swap(ids);
  for (Node& node : nodes_) {
    if (node.dim == kPointLeaf) {
      node.child[0] = static_cast<int32_t>(renamed[node.child[0]]);
    } else if (node.dim == kBlockLeaf) {
      for (int32_t i = 0; i < node.child[1]; ++i) {
        uint32_t& point = pool_[node.child[0] + i];
        point = renamed[point];
      }
    }
  }
}

void KdForest::CompactLeaves() {
  std::vector<uint32_t, HugePageAllocator<uint32_t>> pool;
  size_t entries = 0;
  for (const Node& node : nodes_) {
    if (node.dim == kBlockLeaf) entries += 1 + node.child[1];
  }
  pool.reserve(entries);
  // Only the leaves reachable from the roots: an insertion that split a leaf
  // leaves the old node and block behind until a rebuild.
  std::vector<int32_t> stack(roots_.begin(), roots_.end());
  while (!stack.empty()) {
    Node& node = nodes_[stack.back()];
    stack.pop_back();
    if (node.dim >= 0) {
      stack.push_back(node.child[1]);
      stack.push_back(node.child[0]);
      continue;
    }
    if (node.dim != kBlockLeaf) continue;
    const int32_t count = node.child[1];
    const uint32_t* points = &pool_[node.child[0]];
    if (count == 1) {
      node.dim = kPointLeaf;
      node.child[0] = static_cast<int32_t>(points[0]);
      continue;
    }
    pool.push_back(static_cast<uint32_t>(count));
    node.child[0] = static_cast<int32_t>(pool.size());
    pool.insert(pool.end(), points, points + count);
  }
  pool.shrink_to_fit();
  pool_.swap(pool);
  slot_.Pack();
}

void KdForest::Insert(int tree, uint32_t p) {
  const int32_t n = LeafOf(tree, p);
  const int32_t count = nodes_[n].child[1];
  if (count + 1 > options_.leaf_size) {
    // Too many for one leaf: split the leaf's points and the new one.
    const uint32_t* held = LeafPoints(nodes_[n]);
    std::vector<uint32_t> points(held, held + count);
    points.push_back(p);
    const size_t nodes_before = nodes_.size();
    const size_t pool_before = pool_.size();
    const int32_t sub = Divide(&points, 0, points.size());
    if (nodes_[sub].dim >= 0) {
      // The subtree's root slot and the old block stay unused until a rebuild.
      nodes_[n] = nodes_[sub];
      return;
    }
    // Rows identical on every sampled dimension: keep them in one leaf.
    nodes_.resize(nodes_before);
    pool_.resize(pool_before);
  }
  Node& leaf = nodes_[n];
  if (leaf.dim == kPointLeaf) {
    const uint32_t first = static_cast<uint32_t>(leaf.child[0]);
    const uint32_t capacity = static_cast<uint32_t>(std::max(2, options_.leaf_size + 1));
    leaf.child[0] = AppendBlock(&first, 1, capacity);
    leaf.dim = kBlockLeaf;
  } else if (static_cast<uint32_t>(count) == pool_[leaf.child[0] - 1]) {  // full: grow
    const uint32_t capacity = 2 * pool_[leaf.child[0] - 1];
    const int32_t old_offset = leaf.child[0];
    leaf.child[0] = AppendBlock(nullptr, 0, capacity);
    std::copy_n(pool_.begin() + old_offset, count, pool_.begin() + leaf.child[0]);
  }
  pool_[leaf.child[0] + count] = p;
  leaf.child[1] = count + 1;
}

void KdForest::Add(WordId id, const uint8_t* row) {
  SLAM_CHECK(id > 0 && !Contains(id));
  const uint32_t p = static_cast<uint32_t>(ids_.size());
  data_.insert(data_.end(), row, row + row_bytes_);
  ids_.push_back(id);
  slot_.Set(id, p);
  if (roots_.empty() || ids_.size() > rows_at_build_ * options_.rebuild_factor) {
    Rebuild();
    return;
  }
  for (int t = 0; t < options_.trees; ++t) Insert(t, p);
}

bool KdForest::Remove(WordId id) {
  const uint32_t p = slot_.Find(id);
  if (p == WordSlots::kNone) return false;
  // The point stays in its leaves, skipped by its id, until a rebuild.
  ids_[p] = kNoWord;
  slot_.Erase(id);
  if (slot_.empty()) Rebuild();  // frees everything
  return true;
}

bool KdForest::Visit(uint32_t p) const {
  if (2 * (visited_count_ + 1) > visited_.size()) {  // keep the load at most 1/2
    std::vector<uint32_t> old(std::max<size_t>(256, 2 * visited_.size()), 0u);
    old.swap(visited_);
    visited_count_ = 0;
    for (uint32_t key : old) {
      if (key != 0) Visit(key - 1);
    }
  }
  const size_t mask = visited_.size() - 1;
  for (size_t slot = (p * 2654435761u) & mask;; slot = (slot + 1) & mask) {
    if (visited_[slot] == p + 1) return false;
    if (visited_[slot] == 0) {
      visited_[slot] = p + 1;
      ++visited_count_;
      return true;
    }
  }
}

int32_t KdForest::Step(int32_t n, const uint8_t* q, float mindist,
                       std::vector<std::pair<float, int32_t>>* heap) const {
  const Node& node = nodes_[n];
  const float diff = QueryValue(q, node.dim) - node.split;
  const int near = diff < 0 ? 0 : 1;
  const float far = mindist + (format_ != WordRowFormat::kBinary ? diff * diff : std::abs(diff));
  heap->push_back({far, node.child[1 - near]});
  std::push_heap(heap->begin(), heap->end(), std::greater<>());
  return node.child[near];
}

void KdForest::PrefetchLeafRows(int32_t n) const {
  const uint32_t* points = LeafPoints(nodes_[n]);
  for (int32_t i = 0; i < nodes_[n].child[1]; ++i) {
    __builtin_prefetch(&ids_[points[i]]);
    const uint8_t* row = Data(points[i]);
    for (size_t b = 0; b < row_bytes_; b += 64) __builtin_prefetch(row + b);
  }
}

void KdForest::CheckLeaf(int32_t n, const uint8_t* q, int* checks, KdNeighbour best[2],
                         int* found) const {
  const uint32_t* points = LeafPoints(nodes_[n]);
  const int32_t count = nodes_[n].child[1];
  for (int32_t i = 0; i < count; ++i) {
    const uint32_t p = points[i];
    const WordId id = ids_[p];
    if (id == kNoWord || !Visit(p)) continue;
    ++*checks;
    const uint8_t* row = Data(p);
    if (*found < 2) {
      best[(*found)++] = {id, WordDistance(format_, q, row, cols_, options_.binary_distance)};
      if (*found == 2 && Closer(best[1], best[0])) std::swap(best[0], best[1]);
      continue;
    }
    // Only a row at most as far as the second best can change the result;
    // the bounded distance is exact below the bound and >= it otherwise.
    const float bound = best[1].distance;
    float d = WordDistanceBounded(format_, q, row, cols_, bound, options_.binary_distance);
    if (d > bound) continue;
    if (d == bound) d = WordDistance(format_, q, row, cols_, options_.binary_distance);  // a tie decides by id
    const KdNeighbour c{id, d};
    if (Closer(c, best[1])) {
      best[1] = c;
      if (Closer(best[1], best[0])) std::swap(best[0], best[1]);
    }
  }
}

// Best-bin-first search as FLANN's: one descent per tree, then the queued
// branches nearest first until `checks` rows were compared. The descents of
// the trees are independent, so they go down level by level side by side
// (their cache misses overlap), and the leaves' rows are requested before
// any is compared. The heap orders (distance, node) pairs totally and the
// two best are kept by (distance, id), so the order in which rows are
// compared does not change the result.
void KdForest::SearchTwo(const uint8_t* query, std::vector<KdNeighbour>* out) const {
  out->clear();
  if (slot_.empty()) return;
  std::fill(visited_.begin(), visited_.end(), 0u);
  visited_count_ = 0;
  KdNeighbour best[2];
  int found = 0, checks = 0;
  std::vector<std::pair<float, int32_t>>& heap = heap_;
  heap.clear();
  std::vector<int32_t>& at = descents_;
  at.assign(roots_.begin(), roots_.end());
  for (bool moved = true; moved;) {
    moved = false;
    for (int32_t& n : at) {
      if (nodes_[n].dim < 0) continue;
      n = Step(n, query, 0.0f, &heap);
      __builtin_prefetch(&nodes_[n]);
      moved = true;
    }
  }
  for (int32_t n : at) {
    if (nodes_[n].dim == kBlockLeaf) __builtin_prefetch(&pool_[nodes_[n].child[0]]);
  }
  for (int32_t n : at) PrefetchLeafRows(n);
  for (int32_t n : at) CheckLeaf(n, query, &checks, best, &found);
  while (!heap.empty() && (checks < options_.checks || found < 2)) {
    std::pop_heap(heap.begin(), heap.end(), std::greater<>());
    auto [mindist, n] = heap.back();
    heap.pop_back();
    if (!heap.empty()) __builtin_prefetch(&nodes_[heap.front().second]);  // likely the next
    while (nodes_[n].dim >= 0) n = Step(n, query, mindist, &heap);
    PrefetchLeafRows(n);
    CheckLeaf(n, query, &checks, best, &found);
  }
  out->assign(best, best + found);
}

size_t KdForest::MemoryBytes() const {
  size_t bytes = data_.capacity() + ids_.capacity() * sizeof(WordId) +
                 nodes_.capacity() * sizeof(Node) + pool_.capacity() * sizeof(uint32_t) +
                 visited_.capacity() * sizeof(uint32_t);
  return bytes + slot_.MemoryBytes();
}

}  // namespace duskmap
