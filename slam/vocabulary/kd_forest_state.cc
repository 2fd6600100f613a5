// KdForest::AppendState / KdForest::RestoreState (declared in kd_forest.h).
#include <algorithm>
#include <cmath>
#include <sstream>

#include "slam/core/byte_buffer.h"
#include "slam/vocabulary/kd_forest.h"

namespace duskmap {
namespace {

constexpr uint32_t kStateMagic = 0x3146444b;  // "KDF1"

// The options and row shape that fix a forest's structure (checks only
// bound searches and is not part of it).
struct Shape {
  uint32_t format = 0;
  int32_t cols = 0;
  int32_t trees = 0;
  int32_t leaf_size = 0;
  uint64_t seed = 0;
  double rebuild_factor = 0.0;
  uint32_t binary_distance = 0;

  bool operator==(const Shape& o) const {
    return format == o.format && cols == o.cols && trees == o.trees &&
           leaf_size == o.leaf_size && seed == o.seed && rebuild_factor == o.rebuild_factor &&
           binary_distance == o.binary_distance;
  }
};

std::string Describe(const Shape& s) {
  std::ostringstream text;
  text << "format " << s.format << ", " << s.cols << " columns, " << s.trees << " trees, leaf size "
       << s.leaf_size << ", seed " << s.seed << ", rebuild factor " << s.rebuild_factor
       << ", binary distance "
       << BinaryDistanceName(static_cast<BinaryDistance>(s.binary_distance));
  return text.str();
}

Shape ShapeOf(const KdForest& forest) {
  const KdForestOptions& o = forest.options();
  return Shape{static_cast<uint32_t>(forest.format()), forest.cols(), o.trees, o.leaf_size,
               o.seed, o.rebuild_factor, static_cast<uint32_t>(o.binary_distance)};
}

}  // namespace

void KdForest::AppendState(std::vector<uint8_t>* out) const {
  ByteWriter w(out);
  w.Put(kStateMagic);
  const Shape shape = ShapeOf(*this);
  w.Put(shape.format);
  w.Put(shape.cols);
  w.Put(shape.trees);
  w.Put(shape.leaf_size);
  w.Put(shape.seed);
  w.Put(shape.rebuild_factor);
  w.Put(shape.binary_distance);
  w.PutVector(ids_);
  w.Put<uint64_t>(rows_at_build_);
  w.Put<int32_t>(rebuilds_);
  w.PutVector(nodes_);
  w.PutVector(pool_);
  w.PutVector(roots_);
  std::ostringstream rng;
  rng << rng_;
  w.PutString(rng.str());
}

bool KdForest::RestoreState(const uint8_t* state, size_t size, const std::vector<WordId>& ids,
                            const uint8_t* rows, std::string* problem) {
  SLAM_CHECK(problem != nullptr && slot_.empty() && ids_.empty());
  auto fail = [&](const std::string& why) {
    *problem = why;
    data_.clear();
    ids_.clear();
    slot_.Clear();
    nodes_.clear();
    pool_.clear();
    roots_.clear();
    rows_at_build_ = 0;
    rebuilds_ = 0;
    rng_.seed(options_.seed);
    return false;
  };
  ByteReader r(state, size);
  uint32_t magic = 0;
  Shape saved;
  if (!r.Get(&magic) || magic != kStateMagic) return fail("not a KD-forest state");
  if (!r.Get(&saved.format) || !r.Get(&saved.cols) || !r.Get(&saved.trees) ||
      !r.Get(&saved.leaf_size) || !r.Get(&saved.seed) || !r.Get(&saved.rebuild_factor) ||
      !r.Get(&saved.binary_distance)) {
    return fail("KD-forest state truncated in its header");
  }
  const Shape mine = ShapeOf(*this);
  if (!(saved == mine)) {
    return fail("the stored index was built with other options (" + Describe(saved) +
                "; this run uses " + Describe(mine) + ")");
  }
  std::vector<WordId> point_ids;
  uint64_t rows_at_build = 0;
  int32_t rebuilds = 0;
  std::string rng_text;
  if (!r.GetVector(&point_ids) || !r.Get(&rows_at_build) || !r.Get(&rebuilds) ||
      !r.GetVector(&nodes_) || !r.GetVector(&pool_) ||
      !r.GetVector(&roots_, static_cast<uint64_t>(options_.trees)) || !r.GetString(&rng_text)) {
    return fail("KD-forest state truncated");
  }
  if (r.remaining() != 0) return fail("KD-forest state has trailing bytes");
  if (point_ids.size() != ids.size()) {
    return fail("the stored index holds " + std::to_string(point_ids.size()) + " words, the map " +
                std::to_string(ids.size()));
  }
  if (roots_.size() != static_cast<size_t>(options_.trees) && !ids.empty()) {
    return fail("the stored index has " + std::to_string(roots_.size()) + " trees");
  }
  std::istringstream rng_in(rng_text);
  rng_in >> rng_;
  if (rng_in.fail()) return fail("the stored index's random generator state is unreadable");
  // Points -> ids: a permutation of the words.
  if (!ids.empty()) slot_.Reserve(ids.back());
  ids_.reserve(point_ids.size());
  data_.resize(point_ids.size() * row_bytes_);
  for (uint32_t p = 0; p < point_ids.size(); ++p) {
    const WordId id = point_ids[p];
    const auto it = std::lower_bound(ids.begin(), ids.end(), id);
    if (it == ids.end() || *it != id || slot_.Contains(id)) {
      return fail("the stored index names word " + std::to_string(id) +
                  ", which the map does not have (or twice)");
    }
    const size_t row = static_cast<size_t>(it - ids.begin());
    std::copy_n(rows + row * row_bytes_, row_bytes_, &data_[static_cast<size_t>(p) * row_bytes_]);
    slot_.Set(id, p);
    ids_.push_back(id);
  }
  rows_at_build_ = rows_at_build;
  rebuilds_ = rebuilds;
  if (const std::string why = CheckStructure(); !why.empty()) return fail(why);
  slot_.Pack();  // a stored index is searched, not grown (word_slots.h)
  return true;
}

std::string KdForest::CheckStructure() const {
  const size_t n = ids_.size();
  if (n == 0) return nodes_.empty() && roots_.empty() ? "" : "an empty stored index has trees";
  std::vector<uint8_t> reached(nodes_.size(), 0);
  std::vector<uint32_t> covered(n, 0);
  std::vector<int32_t> stack;
  for (size_t t = 0; t < roots_.size(); ++t) {
    size_t leaf_points = 0;
    stack.assign(1, roots_[t]);
    while (!stack.empty()) {
      const int32_t index = stack.back();
      stack.pop_back();
      if (index < 0 || static_cast<size_t>(index) >= nodes_.size()) return "a tree node is out of range";
      if (reached[index]) return "a tree node is reached twice";
      reached[index] = 1;
      const Node& node = nodes_[index];
      if (node.dim >= 0) {
        if (node.dim >= dims_ || !std::isfinite(node.split)) return "a split is invalid";
        stack.push_back(node.child[1]);
        stack.push_back(node.child[0]);
        continue;
      }
      const int32_t count = node.child[1];
      const uint32_t* points = nullptr;
      if (node.dim == kPointLeaf) {
        if (count != 1) return "a point leaf holds more than one point";
        points = reinterpret_cast<const uint32_t*>(&node.child[0]);
      } else if (node.dim == kBlockLeaf) {
        const int64_t offset = node.child[0];
        if (count < 1 || offset < 1 || offset + count > static_cast<int64_t>(pool_.size()) ||
            pool_[offset - 1] < static_cast<uint32_t>(count) ||
            static_cast<size_t>(offset) + pool_[offset - 1] > pool_.size()) {
          return "a leaf block is out of range";
        }
        points = &pool_[offset];
      } else {
        return "a tree node has an unknown kind";
      }
      for (int32_t i = 0; i < count; ++i) {
        if (points[i] >= n) return "a leaf names a point out of range";
        if (covered[points[i]] != t) return "a point is in two leaves of one tree";
        covered[points[i]] = static_cast<uint32_t>(t + 1);
      }
      leaf_points += static_cast<size_t>(count);
    }
    if (leaf_points != n) return "a tree does not hold every word";
  }
  return "";
}

}  // namespace duskmap
