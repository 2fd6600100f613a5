// Randomized KD-trees with incremental insertion, lazy removal and a rebuild
// when the number of rows has doubled since the last build: the structure of
// FLANN's KDTreeIndex as RTAB-Map uses it (spec §2.3), reimplemented because
// Debian's FLANN shuffles with std::random_device and therefore builds
// different trees on every run (measured: two identical vocabularies diverge
// after a few frames). Every random choice here comes from a seeded Rng.
//
// Float rows are compared with squared L2, stored as floats or quantized to
// 8 bits (WordRowFormat::kQuantized8: queries stay floats, splits and
// distances use the quantized values). Binary rows are either bit vectors
// (one dimension per bit, as the reference's byte-to-bits expansion) compared
// with Hamming distance directly on the packed bytes, or byte vectors (one
// dimension per byte, its Kp/ByteToFloat) compared by the L1 of the byte
// values (KdForestOptions::binary_distance).
#pragma once

#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include "slam/core/random.h"
#include "slam/vocabulary/word_slots.h"
#include "slam/vocabulary/word_types.h"

namespace duskmap {

// Allocator for the forest's large arrays: blocks of 4 MiB and more are
// 2 MiB-aligned and, on Linux, advised to be backed by transparent huge
// pages before they are first touched. The rows are read at random, so with
// 4 KiB pages nearly every row costs a TLB miss as well as a cache miss.
template <typename T>
struct HugePageAllocator {
  using value_type = T;
  HugePageAllocator() = default;
  template <typename U>
  HugePageAllocator(const HugePageAllocator<U>&) {}
  T* allocate(size_t n);
  void deallocate(T* p, size_t) { std::free(p); }
  template <typename U>
  bool operator==(const HugePageAllocator<U>&) const { return true; }
  template <typename U>
  bool operator!=(const HugePageAllocator<U>&) const { return false; }
};

// Allocates `bytes` (huge-page advised when large); throws std::bad_alloc.
void* AllocateHugePageAdvised(size_t bytes);

template <typename T>
T* HugePageAllocator<T>::allocate(size_t n) {
  return static_cast<T*>(AllocateHugePageAdvised(n * sizeof(T)));
}

struct KdForestOptions {
  int trees = 4;                 // randomized trees (reference: 4)
  int checks = 32;               // leaf rows compared per search (reference KNN_CHECKS: 32)
  int leaf_size = 1;             // rows per leaf before it splits (FLANN: 1)
  double rebuild_factor = 2.0;   // rebuild when rows (removed included) > factor x rows at build
  uint64_t seed = 42;            // all random choices (shuffles, split dimensions)
  BinaryDistance binary_distance = BinaryDistance::kHamming;  // binary rows only
};

struct KdNeighbour {
  WordId id = kNoWord;
  float distance = 0.0f;
};

class KdForest {
 public:
  // `cols`: elements (floats or bytes) per extracted row.
  KdForest(const KdForestOptions& options, WordRowFormat format, int cols);

  // `row`: WordRowBytes(format, cols) bytes in the stored format.
  void Add(WordId id, const uint8_t* row);  // id must be new
  bool Remove(WordId id);                   // false when absent
  bool Contains(WordId id) const { return slot_.Contains(id); }
  // The stored row; valid until the next Add or Rebuild.
  const uint8_t* Row(WordId id) const;
  WordRowFormat format() const { return format_; }
  int cols() const { return cols_; }
  const KdForestOptions& options() const { return options_; }
  // Up to 2 nearest live rows of an extracted query row, nearest first.
  void SearchTwo(const uint8_t* query, std::vector<KdNeighbour>* out) const;
  // Drops removed rows and builds every tree again.
  void Rebuild();
  // Gives every block leaf exactly the entries it holds (a build leaves room
  // for leaf_size + 1 so that insertions rarely move a block): for a forest
  // that will not grow, e.g. an imported vocabulary used for localization,
  // and packs the id table (word_slots.h). Searches are unchanged; a later
  // Add still works (a full block moves, the id table turns dense again).
  void CompactLeaves();
  // Reserves the id table for ids up to `max_id`.
  void ReserveIds(WordId max_id) { slot_.Reserve(max_id); }

  // The forest's structure as bytes (kd_forest_state.cc): the options that
  // shape it, the point order, the trees, the build counters and the random
  // generator's state; not the rows, which the words hold. For a map that
  // stores its vocabulary's index, so that a load need not build it again.
  void AppendState(std::vector<uint8_t>* out) const;
  // Restores AppendState's bytes into this forest, which must be empty:
  // `ids` (strictly increasing) and `rows` (their stored rows, contiguous,
  // in the same order) must be the live rows of the saved forest. The
  // result equals the saved forest: the same searches, the same future
  // insertions and rebuilds. Returns false with `*problem` set (the forest
  // left empty) when the bytes were saved with other options, name other
  // words, or do not describe a valid forest.
  bool RestoreState(const uint8_t* state, size_t size, const std::vector<WordId>& ids,
                    const uint8_t* rows, std::string* problem);

  size_t size() const { return slot_.size(); }
  int rebuild_count() const { return rebuilds_; }
  size_t MemoryBytes() const;

 private:
  // Inner node: dim >= 0, children child[0] (value < split) and child[1].
  // Leaf, one of two kinds (child[1] is its point count in both):
  //  - kPointLeaf: its single point is child[0] itself, no block (leaf_size
  //    1, FLANN's, makes nearly every leaf one of these);
  //  - kBlockLeaf: its points are pool_[child[0], child[0] + child[1]) and
  //    pool_[child[0] - 1] holds the block's capacity.
  // Removed points stay in their leaves until a rebuild; ids_ marks them.
  static constexpr int32_t kBlockLeaf = -1;
  static constexpr int32_t kPointLeaf = -2;
  struct Node {
    int32_t dim = kBlockLeaf;
    float split = 0.0f;
    int32_t child[2] = {-1, -1};
  };
  // The points of a leaf (child[1] of them).
  const uint32_t* LeafPoints(const Node& leaf) const;
  float Value(uint32_t p, int dim) const;
  float QueryValue(const uint8_t* q, int dim) const;
  int32_t Divide(std::vector<uint32_t>* idx, size_t begin, size_t end);
  int32_t MakeLeaf(const std::vector<uint32_t>& idx, size_t begin, size_t end);
  // Appends a block of `capacity` entries holding `points` (count of them)
  // after its capacity word; returns the offset of the first entry.
  int32_t AppendBlock(const uint32_t* points, int32_t count, uint32_t capacity);
  // The leaf of `tree` that holds (or would hold) point p.
  int32_t LeafOf(int tree, uint32_t p) const;
  void Insert(int tree, uint32_t p);
  // RestoreState's structural checks: every tree a tree over all points,
  // every node reached once. "" when valid.
  std::string CheckStructure() const;
  // Renumbers the points so that the rows of each leaf of the first tree are
  // adjacent in data_ (fewer cache misses per leaf; results are unchanged).
  void RenumberByLeaves();
  // One level down from inner node n: queues the far child (best-bin-first
  // heap) and returns the near one.
  int32_t Step(int32_t n, const uint8_t* q, float mindist,
               std::vector<std::pair<float, int32_t>>* heap) const;
  void PrefetchLeafRows(int32_t leaf) const;
  // Compares the query with the rows of a leaf not compared yet.
  void CheckLeaf(int32_t leaf, const uint8_t* q, int* checks, KdNeighbour best[2], int* found) const;
  // Marks p as compared by this search; false when it already was.
  bool Visit(uint32_t p) const;
  const uint8_t* Data(uint32_t p) const { return &data_[static_cast<size_t>(p) * row_bytes_]; }

  KdForestOptions options_;
  WordRowFormat format_;
  int cols_;
  int dims_;
  size_t row_bytes_;
  Rng rng_;
  std::vector<uint8_t, HugePageAllocator<uint8_t>> data_;  // rows by point index (removed rows until a rebuild)
  std::vector<WordId> ids_;             // point -> id (kNoWord once removed)
  WordSlots slot_;                      // id -> point
  std::vector<Node, HugePageAllocator<Node>> nodes_;
  std::vector<uint32_t, HugePageAllocator<uint32_t>> pool_;  // block leaves' points (see Node)
  std::vector<int32_t> roots_;
  size_t rows_at_build_ = 0;
  int rebuilds_ = 0;
  mutable std::vector<uint32_t> visited_;  // open-addressing set of point + 1 (0 = empty)
  mutable size_t visited_count_ = 0;
  mutable std::vector<std::pair<float, int32_t>> heap_;  // search scratch
  mutable std::vector<int32_t> descents_;                 // search scratch: one node per tree
};

}  // namespace duskmap
