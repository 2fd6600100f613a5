// Nearest-neighbour index over the descriptors of the visual words, with
// incremental insertion and removal (reference: corelib/src/FlannIndex.cpp).
// The index owns the word descriptors; FLANN keeps pointers to them, so a
// removed word's row stays allocated until the next rebuild drops it.
// KD-tree kinds use the own deterministic KdForest (kd_forest.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "slam/vocabulary/word_types.h"

namespace duskmap {

enum class IndexKind {
  kKdTree,        // float only: seeded randomized KD-trees (KdForest), squared L2 —
                  // reference Kp/NNStrategy=1
  kBitKdTree,     // binary only: KdForest over the bits (one dimension per bit), Hamming —
                  // the reference's byte-to-bits KD-tree with L1, Kp/NNStrategy=1; with
                  // binary_distance byte_l1 over the bytes (one dimension per byte), L1 —
                  // its Kp/ByteToFloat
  kLsh,           // binary only: multi-probe LSH (Kp/NNStrategy=2), FLANN's method in own
                  // code (FLANN's LshTable overflows and over-reads), key bits drawn from `seed`
  kHierarchical,  // binary only: FLANN hierarchical clustering, Hamming; NOT deterministic
  kLinear,        // exact brute force (float or binary); for tests and small maps
};

const char* IndexKindName(IndexKind kind);
// Parses "kdtree", "bit_kdtree", "lsh", "hierarchical", "linear"; throws ConfigError.
IndexKind ParseIndexKind(const std::string& name);

struct DescriptorIndexOptions {
  IndexKind float_kind = IndexKind::kKdTree;    // index used for float descriptors
  IndexKind binary_kind = IndexKind::kBitKdTree;  // index used for binary descriptors
  int kd_trees = 4;               // randomized KD-trees (reference: 4)
  int kd_leaf_size = 4;           // rows per KD-tree leaf before it splits (FLANN: 1)
  int checks = 32;                // rows compared per search (reference KNN_CHECKS: 32)
  double rebalancing_factor = 2.0;  // rebuild when rows >= factor x rows at last build
  int lsh_tables = 12;            // LSH hash tables, 1-256 (reference: 12)
  int lsh_key_bits = 20;          // LSH key size, bits, 1-32, at most the row's (reference: 20)
  int lsh_multi_probe = 2;        // LSH multi-probe level: probes keys with up to this many bits
                                  // flipped, at most 65536 per table (reference: 2); LSH
                                  // ignores `checks`
  int hierarchical_branching = 32;  // hierarchical clustering branching factor
  int hierarchical_trees = 4;       // hierarchical clustering trees
  int hierarchical_leaf_size = 100; // hierarchical clustering max leaf size, rows
  uint32_t seed = 42;             // seeds the KD-trees' and LSH keys' random choices (and srand
                                  // for FLANN)
  // How float words are stored: as extracted, or 8-bit per element with a
  // per-row offset and step (kdtree and linear kinds; a quarter of the
  // bytes, distances against the quantized values). Binary words are exact.
  DescriptorStorage float_storage = DescriptorStorage::kFloat32;
  // How binary words are compared (binary_distance.h): Hamming, the
  // reference's default, or the L1 of the byte values, its Kp/ByteToFloat
  // (the paper's runs). For the bit_kdtree and linear kinds; LSH and
  // hierarchical clustering compare by Hamming only.
  BinaryDistance binary_distance = BinaryDistance::kHamming;

  void Check() const;
};

// One neighbour found by a search: the word and its distance (squared L2,
// Hamming or byte L1, see DescriptorDistance).
struct WordNeighbour {
  WordId word = kNoWord;
  float distance = 0.0f;
};

class DescriptorIndex {
 public:
  // `cols`: elements per row (128 floats for SIFT, 32 bytes for ORB).
  DescriptorIndex(const DescriptorIndexOptions& options, DescriptorKind kind, int cols);
  ~DescriptorIndex();
  DescriptorIndex(const DescriptorIndex&) = delete;
  DescriptorIndex& operator=(const DescriptorIndex&) = delete;

  DescriptorKind kind() const { return kind_; }
  int cols() const { return cols_; }
  // Bytes of an extracted row (queries, Add).
  size_t row_bytes() const;
  // The stored form of a word and its size.
  WordRowFormat format() const;
  size_t stored_row_bytes() const;
  IndexKind index_kind() const;

  // Stores `row` (an extracted row, row_bytes() bytes) in format() and
  // indexes it under `word`, which must not be present. Rebuilds when the
  // index has doubled since its last build. Throws InputError for a float
  // row with a non-finite value when words are quantized.
  void Add(WordId word, const uint8_t* row);
  // The same with a row already in the stored form (stored_row_bytes()).
  void AddStored(WordId word, const uint8_t* stored_row);
  // Removes `word` from the searchable set. Returns false when absent.
  bool Remove(WordId word);
  bool Contains(WordId word) const;
  // The stored row of a present word (format(), stored_row_bytes() bytes).
  const uint8_t* StoredRow(WordId word) const;

  // Up to two nearest live words of each query row (`queries`: rows x
  // row_bytes(), contiguous). out->size() == rows on return.
  void SearchTwoNearest(const uint8_t* queries, int rows,
                        std::vector<std::vector<WordNeighbour>>* out) const;

  // Rebuilds every tree from the live words now (a "batch" build).
  void Rebuild();
  // Releases what only growth needs (KD-forest leaf slack; nothing for the
  // FLANN and linear kinds), for an index that will not grow. Searches are
  // unchanged.
  void Compact();
  // Reserves id bookkeeping for ids up to `max_id`.
  void ReserveIds(WordId max_id);

  // Whether SaveState can store this index: the KD-tree kinds (kdtree,
  // bit_kdtree), which are deterministic; the FLANN kinds rebuild on load.
  bool CanSaveState() const;
  // The built index as bytes (index and descriptor kind, then the
  // KD-forest's shape and structure, kd_forest.h); empty when !CanSaveState().
  std::vector<uint8_t> SaveState() const;
  // Restores SaveState's bytes into this index, which must be empty, with
  // its words given as `ids` (strictly increasing) and their stored rows
  // (`rows`, contiguous, stored_row_bytes() each). The result searches,
  // grows and rebuilds exactly as the saved index. Returns false with
  // `*problem` set, the index left empty, when the bytes belong to another
  // kind, options or words, or are damaged.
  bool RestoreState(const std::vector<uint8_t>& state, const std::vector<WordId>& ids,
                    const uint8_t* rows, std::string* problem);

  size_t size() const;          // live words
  int rebuild_count() const;    // full builds so far (first build included)
  // Bytes held: descriptors, expanded rows, FLANN bookkeeping and trees
  // (trees estimated from their node counts), id maps.
  size_t MemoryBytes() const;

  class Backend;

 private:
  DescriptorKind kind_;
  int cols_;
  std::unique_ptr<Backend> backend_;
};

}  // namespace duskmap
