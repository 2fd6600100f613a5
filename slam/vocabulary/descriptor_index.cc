#include "slam/vocabulary/descriptor_index.h"

#include <algorithm>
#include <numeric>
#include <unordered_map>

#include <flann/flann.hpp>

#include "slam/core/byte_buffer.h"
#include "slam/core/check.h"
#include "slam/core/random.h"
#include "slam/features/binary_distance.h"
#include "slam/vocabulary/kd_forest.h"

namespace duskmap {
namespace {

constexpr int kNeighbours = 2;

// The two nearest words offered so far, ties broken by word id (the linear
// and LSH searches).
class NearestTwo {
 public:
  bool Holds(WordId word) const {
    return (count_ > 0 && best_[0].word == word) || (count_ > 1 && best_[1].word == word);
  }
  void Offer(const WordNeighbour& candidate) {
    if (count_ < kNeighbours) {
      best_[count_++] = candidate;
      if (count_ == 2 && Closer(best_[1], best_[0])) std::swap(best_[0], best_[1]);
    } else if (Closer(candidate, best_[1])) {
      best_[1] = candidate;
      if (Closer(best_[1], best_[0])) std::swap(best_[0], best_[1]);
    }
  }
  void AssignTo(std::vector<WordNeighbour>* out) const { out->assign(best_, best_ + count_); }

 private:
  static bool Closer(const WordNeighbour& a, const WordNeighbour& b) {
    return a.distance < b.distance || (a.distance == b.distance && a.word < b.word);
  }
  WordNeighbour best_[kNeighbours];
  int count_ = 0;
};
// Bucket keys probed per LSH table and query (multi-probe masks), at most.
constexpr size_t kMaxLshProbes = 65536;

// Keys within `level` flipped bits of a `bits`-bit key: sum of C(bits, l)
// for l <= level, stopping once it passes `cap`.
size_t LshProbeCount(int bits, int level, size_t cap) {
  size_t total = 0, term = 1;  // term = C(bits, l)
  for (int l = 0; l <= level && l <= bits; ++l) {
    total += term;
    if (total > cap) return total;
    term = term * static_cast<size_t>(bits - l) / static_cast<size_t>(l + 1);
  }
  return total;
}

// Multi-probe LSH over binary rows (FLANN's method: each table hashes a row
// to the bits it reads at `key_bits` random positions; a search probes the
// buckets of every key within `multi_probe` flipped bits of the query's key
// in every table and compares each word found by Hamming distance over the
// whole row). Own code instead of FLANN's LshIndex, whose LshTable<uchar>
// negates a 64-bit block as a signed integer when a key uses its top bit
// (UB, lsh_table.h:419), reads rows in 8-byte blocks past the end of rows
// that are not a multiple of 8 bytes, reads past its bit list when the key is
// longer than the row, leaves the bytes after the last whole 8-byte block out
// of its Hamming distance, and draws its bits with std::random_device. Here
// the bits come from the seed, so the index is deterministic. Words enter
// and leave the buckets at once: the tables never need a rebuild.
class LshTables {
 public:
  LshTables(const DescriptorIndexOptions& options, int cols) : cols_(cols) {
    const int row_bits = cols * 8;
    const int key_bits = std::min(options.lsh_key_bits, row_bits);
    Rng rng(DeriveSeed(options.seed, 0x4C5348));  // "LSH"
    std::vector<int> positions(row_bits);
    tables_.resize(options.lsh_tables);
    for (Table& table : tables_) {
      std::iota(positions.begin(), positions.end(), 0);
      for (int i = 0; i < key_bits; ++i) {  // partial Fisher-Yates shuffle
        const int j = i + static_cast<int>(rng() % static_cast<uint64_t>(row_bits - i));
        std::swap(positions[i], positions[j]);
      }
      table.bits.assign(positions.begin(), positions.begin() + key_bits);
      std::sort(table.bits.begin(), table.bits.end());
    }
    AddMasks(0, key_bits, options.lsh_multi_probe);
  }

  void Add(WordId word, const uint8_t* row) {
    for (Table& table : tables_) table.buckets[Key(table, row)].push_back({word, row});
  }
  void Remove(WordId word, const uint8_t* row) {
    for (Table& table : tables_) {
      auto bucket = table.buckets.find(Key(table, row));
      SLAM_CHECK(bucket != table.buckets.end());
      std::vector<Entry>& entries = bucket->second;
      auto it = std::find_if(entries.begin(), entries.end(),
                             [word](const Entry& e) { return e.word == word; });
      SLAM_CHECK(it != entries.end());
      *it = entries.back();
      entries.pop_back();
      if (entries.empty()) table.buckets.erase(bucket);
    }
  }
  // The two nearest words among the probed buckets, ties by word id.
  void SearchTwo(const uint8_t* query, std::vector<WordNeighbour>* out) const {
    NearestTwo nearest;
    for (const Table& table : tables_) {
      const uint32_t key = Key(table, query);
      for (const uint32_t mask : masks_) {
        const auto bucket = table.buckets.find(key ^ mask);
        if (bucket == table.buckets.end()) continue;
        for (const Entry& e : bucket->second) {
          // Already held (found through another table or probe).
          if (nearest.Holds(e.word)) continue;
          nearest.Offer({e.word, DescriptorDistance(DescriptorKind::kBinary, query, e.row, cols_)});
        }
      }
    }
    nearest.AssignTo(out);
  }
  // Bucket entries and hash nodes (the rows belong to the caller).
  size_t MemoryBytes() const {
    size_t bytes = masks_.capacity() * sizeof(uint32_t);
    for (const Table& table : tables_) {
      bytes += table.bits.capacity() * sizeof(int) + table.buckets.bucket_count() * sizeof(void*);
      for (const auto& bucket : table.buckets) {
        bytes += bucket.second.capacity() * sizeof(Entry) + sizeof(bucket) + 2 * sizeof(void*);
      }
    }
    return bytes;
  }

 private:
  struct Entry {
    WordId word;
    const uint8_t* row;  // the caller's stored row, alive while the word is indexed
  };
  struct Table {
    std::vector<int> bits;  // row bit positions, key bit i = row bit bits[i]
    std::unordered_map<uint32_t, std::vector<Entry>> buckets;
  };

  static uint32_t Key(const Table& table, const uint8_t* row) {
    uint32_t key = 0;
    for (size_t i = 0; i < table.bits.size(); ++i) {
      const int b = table.bits[i];
      key |= static_cast<uint32_t>((row[b >> 3] >> (b & 7)) & 1u) << i;
    }
    return key;
  }
  // FLANN's fill_xor_mask: every key with at most `level` bits set below `lowest`.
  void AddMasks(uint32_t mask, int lowest, int level) {
    masks_.push_back(mask);
    if (level == 0) return;
    for (int i = lowest - 1; i >= 0; --i) AddMasks(mask | (uint32_t{1} << i), i, level - 1);
  }

  int cols_;
  std::vector<Table> tables_;
  std::vector<uint32_t> masks_;
};

// Type-erased FLANN index over row pointers owned by DescriptorIndex::Backend.
class FlannHolder {
 public:
  virtual ~FlannHolder() = default;
  // Adds one row; FLANN rebuilds inside when rows_at_build * factor < rows.
  virtual void AddRow(const void* row, float rebuild_factor) = 0;
  virtual void RemoveRow(size_t flann_id) = 0;
  virtual void BuildNow() = 0;
  // k nearest of one query row; ids are FLANN ids, distances as floats.
  virtual int Knn(const void* query, int k, int checks, size_t* ids, float* dists) const = 0;
};

template <typename Dist>
class FlannHolderT : public FlannHolder {
 public:
  using Element = typename Dist::ElementType;
  using Result = typename Dist::ResultType;

  FlannHolderT(const flann::IndexParams& params, int cols, const void* first_row, uint32_t seed)
      : cols_(cols), seed_(seed) {
    flann::Matrix<Element> m(const_cast<Element*>(static_cast<const Element*>(first_row)), 1,
                             cols);
    index_ = std::make_unique<flann::Index<Dist>>(m, params);
    BuildNow();
  }
  void AddRow(const void* row, float rebuild_factor) override {
    flann::Matrix<Element> m(const_cast<Element*>(static_cast<const Element*>(row)), 1, cols_);
    flann::seed_random(seed_);
    index_->addPoints(m, rebuild_factor);
  }
  void RemoveRow(size_t flann_id) override { index_->removePoint(flann_id); }
  void BuildNow() override {
    flann::seed_random(seed_);
    index_->buildIndex();
  }
  int Knn(const void* query, int k, int checks, size_t* ids, float* dists) const override {
    flann::Matrix<Element> q(const_cast<Element*>(static_cast<const Element*>(query)), 1, cols_);
    flann::Matrix<size_t> indices(ids, 1, k);
    Result raw[kNeighbours];
    flann::Matrix<Result> distances(raw, 1, k);
    flann::SearchParams params(checks);
    for (int i = 0; i < k; ++i) {
      ids[i] = static_cast<size_t>(-1);
      raw[i] = Result();
    }
    const int found = index_->knnSearch(q, indices, distances, k, params);
    for (int i = 0; i < k; ++i) dists[i] = static_cast<float>(raw[i]);
    return found;
  }

 private:
  int cols_;
  uint32_t seed_;
  std::unique_ptr<flann::Index<Dist>> index_;
};

}  // namespace

const char* IndexKindName(IndexKind kind) {
  switch (kind) {
    case IndexKind::kKdTree: return "kdtree";
    case IndexKind::kBitKdTree: return "bit_kdtree";
    case IndexKind::kLsh: return "lsh";
    case IndexKind::kHierarchical: return "hierarchical";
    case IndexKind::kLinear: return "linear";
  }
  return "unknown";
}

IndexKind ParseIndexKind(const std::string& name) {
  for (IndexKind k : {IndexKind::kKdTree, IndexKind::kBitKdTree, IndexKind::kLsh,
                      IndexKind::kHierarchical, IndexKind::kLinear}) {
    if (name == IndexKindName(k)) return k;
  }
  throw ConfigError("index kind '" + name +
                    "' unknown (kdtree, bit_kdtree, lsh, hierarchical, linear)");
}

void DescriptorIndexOptions::Check() const {
  SLAM_THROW_IF_NOT(ConfigError, float_kind == IndexKind::kKdTree || float_kind == IndexKind::kLinear)
      << "DescriptorIndexOptions.float_kind: " << IndexKindName(float_kind)
      << " is for binary descriptors (use kdtree or linear)";
  SLAM_THROW_IF_NOT(ConfigError, kd_leaf_size >= 1)
      << "DescriptorIndexOptions.kd_leaf_size must be >= 1, got " << kd_leaf_size;
  SLAM_THROW_IF_NOT(ConfigError, binary_kind != IndexKind::kKdTree)
      << "DescriptorIndexOptions.binary_kind: kdtree needs float rows (use bit_kdtree)";
  SLAM_THROW_IF_NOT(ConfigError, kd_trees >= 1) << "DescriptorIndexOptions.kd_trees must be >= 1, got " << kd_trees;
  SLAM_THROW_IF_NOT(ConfigError, checks >= 1) << "DescriptorIndexOptions.checks must be >= 1, got " << checks;
  SLAM_THROW_IF_NOT(ConfigError, rebalancing_factor > 1.0)
      << "DescriptorIndexOptions.rebalancing_factor must be > 1, got " << rebalancing_factor;
  SLAM_THROW_IF_NOT(ConfigError, lsh_tables >= 1 && lsh_tables <= 256)
      << "DescriptorIndexOptions.lsh_tables must be in [1, 256], got " << lsh_tables;
  SLAM_THROW_IF_NOT(ConfigError, lsh_key_bits >= 1 && lsh_key_bits <= 32)
      << "DescriptorIndexOptions.lsh_key_bits must be in [1, 32], got " << lsh_key_bits;
  SLAM_THROW_IF_NOT(ConfigError, lsh_multi_probe >= 0)
      << "DescriptorIndexOptions.lsh_multi_probe must be >= 0, got " << lsh_multi_probe;
  if (lsh_key_bits >= 1 && lsh_key_bits <= 32) {
    SLAM_THROW_IF_NOT(ConfigError,
                      LshProbeCount(lsh_key_bits, lsh_multi_probe, kMaxLshProbes) <= kMaxLshProbes)
        << "DescriptorIndexOptions.lsh_multi_probe " << lsh_multi_probe << " with "
        << lsh_key_bits << "-bit keys probes more than " << kMaxLshProbes
        << " buckets per table and query (lower lsh_multi_probe or lsh_key_bits)";
  }
  SLAM_THROW_IF_NOT(ConfigError, hierarchical_branching >= 2)
      << "DescriptorIndexOptions.hierarchical_branching must be >= 2, got " << hierarchical_branching;
  SLAM_THROW_IF_NOT(ConfigError, hierarchical_trees >= 1)
      << "DescriptorIndexOptions.hierarchical_trees must be >= 1, got " << hierarchical_trees;
  SLAM_THROW_IF_NOT(ConfigError, binary_distance == BinaryDistance::kHamming ||
                                    binary_kind == IndexKind::kBitKdTree ||
                                    binary_kind == IndexKind::kLinear)
      << "DescriptorIndexOptions.binary_distance: byte_l1 needs binary_kind bit_kdtree or "
         "linear; "
      << IndexKindName(binary_kind) << " compares by Hamming only (set binary_distance hamming)";
  SLAM_THROW_IF_NOT(ConfigError, hierarchical_leaf_size >= 1)
      << "DescriptorIndexOptions.hierarchical_leaf_size must be >= 1, got " << hierarchical_leaf_size;
}

// The Hamming distance over every byte of a row, for FLANN's hierarchical
// index: flann::Hamming<unsigned char> reads rows as 8-byte blocks and leaves
// the bytes after the last whole block out (the last 5 bytes of a 61-byte
// AKAZE row would never count).
struct WholeRowHamming {
  typedef unsigned char ElementType;
  typedef unsigned int ResultType;
  template <typename Iterator1, typename Iterator2>
  ResultType operator()(Iterator1 a, Iterator2 b, size_t size, ResultType /*worst*/ = 0) const {
    return HammingDistance(&a[0], &b[0], static_cast<int>(size));
  }
};

namespace {

// One nearest-neighbour structure over stored word rows (each kind below);
// DescriptorIndex::Backend owns the row format and delegates the rest.
class IndexBackend {
 public:
  virtual ~IndexBackend() = default;
  virtual size_t size() const = 0;
  virtual bool Contains(WordId word) const = 0;
  virtual const uint8_t* StoredRow(WordId word) const = 0;
  // `word` is positive and not held; `row` is a stored row, copied.
  virtual void AddStored(WordId word, const uint8_t* row) = 0;
  virtual bool Remove(WordId word) = 0;
  // The (at most) two nearest words of one query row, nearest first.
  virtual void SearchTwo(const uint8_t* query, std::vector<WordNeighbour>* out) const = 0;
  virtual void Rebuild() = 0;
  virtual int rebuild_count() const = 0;
  virtual size_t MemoryBytes() const = 0;
  // Only the KD-forest kinds compact their leaves, reserve ids and keep their
  // state as bytes.
  virtual void Compact() {}
  virtual void ReserveIds(WordId) {}
  virtual bool CanSaveState() const { return false; }
  virtual void AppendState(std::vector<uint8_t>*) const {}
  virtual bool RestoreState(const uint8_t*, size_t, const std::vector<WordId>&, const uint8_t*,
                            std::string* problem) {
    *problem = "this index kind is not restored from a stored state";
    return false;
  }
};

// kdtree / bit_kdtree: the own KD-forest.
class ForestBackend : public IndexBackend {
 public:
  ForestBackend(const DescriptorIndexOptions& options, WordRowFormat format, int cols) {
    KdForestOptions o;
    o.trees = options.kd_trees;
    o.checks = options.checks;
    o.leaf_size = options.kd_leaf_size;
    o.rebuild_factor = options.rebalancing_factor;
    o.seed = options.seed;
    o.binary_distance = options.binary_distance;
    forest_ = std::make_unique<KdForest>(o, format, cols);
  }
  size_t size() const override { return forest_->size(); }
  bool Contains(WordId word) const override { return forest_->Contains(word); }
  const uint8_t* StoredRow(WordId word) const override { return forest_->Row(word); }
  void AddStored(WordId word, const uint8_t* row) override { forest_->Add(word, row); }
  bool Remove(WordId word) override { return forest_->Remove(word); }
  void SearchTwo(const uint8_t* query, std::vector<WordNeighbour>* out) const override {
    // Searches of one index run on several threads (localizers sharing a map).
    thread_local std::vector<KdNeighbour> found;
    forest_->SearchTwo(query, &found);
    for (const KdNeighbour& k : found) out->push_back({k.id, k.distance});
  }
  void Rebuild() override { forest_->Rebuild(); }
  int rebuild_count() const override { return forest_->rebuild_count(); }
  size_t MemoryBytes() const override { return forest_->MemoryBytes(); }
  void Compact() override { forest_->CompactLeaves(); }
  void ReserveIds(WordId max_id) override { forest_->ReserveIds(max_id); }
  bool CanSaveState() const override { return true; }
  void AppendState(std::vector<uint8_t>* out) const override { forest_->AppendState(out); }
  bool RestoreState(const uint8_t* state, size_t size, const std::vector<WordId>& ids,
                    const uint8_t* rows, std::string* problem) override {
    if (forest_->size() != 0) {
      *problem = "the index already holds words: a stored state restores only an empty one";
      return false;
    }
    return forest_->RestoreState(state, size, ids, rows, problem);
  }

 private:
  std::unique_ptr<KdForest> forest_;
};

// linear: every row compared, contiguous rows.
class LinearBackend : public IndexBackend {
 public:
  LinearBackend(const DescriptorIndexOptions& options, WordRowFormat format, int cols)
      : format_(format), cols_(cols), stored_bytes_(WordRowBytes(format, cols)),
        distance_(options.binary_distance) {}
  size_t size() const override { return words_.size(); }
  bool Contains(WordId word) const override { return slot_of_.count(word) != 0; }
  const uint8_t* StoredRow(WordId word) const override {
    return &rows_[slot_of_.at(word) * stored_bytes_];
  }
  void AddStored(WordId word, const uint8_t* row) override {
    slot_of_.emplace(word, words_.size());
    words_.push_back(word);
    rows_.insert(rows_.end(), row, row + stored_bytes_);
  }
  bool Remove(WordId word) override {
    auto it = slot_of_.find(word);
    if (it == slot_of_.end()) return false;
    const size_t slot = it->second;
    const size_t last = words_.size() - 1;
    if (slot != last) {
      std::copy_n(&rows_[last * stored_bytes_], stored_bytes_, &rows_[slot * stored_bytes_]);
      words_[slot] = words_[last];
      slot_of_.at(words_[slot]) = slot;
    }
    words_.pop_back();
    rows_.resize(last * stored_bytes_);
    slot_of_.erase(it);
    return true;
  }
  void SearchTwo(const uint8_t* query, std::vector<WordNeighbour>* out) const override {
    NearestTwo nearest;
    for (size_t s = 0; s < words_.size(); ++s) {
      nearest.Offer({words_[s], WordDistance(format_, query, &rows_[s * stored_bytes_], cols_, distance_)});
    }
    nearest.AssignTo(out);
  }
  void Rebuild() override {}
  int rebuild_count() const override { return 0; }
  size_t MemoryBytes() const override {
    const size_t n = words_.size();
    return n * (sizeof(WordId) + sizeof(size_t) + 2 * sizeof(void*) + 16) +  // hash node, malloc
           rows_.capacity() + words_.capacity() * sizeof(WordId);
  }

 private:
  WordRowFormat format_;
  int cols_;
  size_t stored_bytes_;
  BinaryDistance distance_;
  std::vector<uint8_t> rows_;
  std::vector<WordId> words_;
  std::unordered_map<WordId, size_t> slot_of_;
};

// Rows held one allocation each (LSH and FLANN keep pointers to them).
using OwnedRow = std::unique_ptr<uint8_t[]>;
OwnedRow CopyRow(const uint8_t* row, size_t bytes) {
  OwnedRow copy(new uint8_t[bytes]);
  std::copy(row, row + bytes, copy.get());
  return copy;
}

// lsh: the own multi-probe LshTables; words enter and leave the buckets at once.
class LshBackend : public IndexBackend {
 public:
  LshBackend(const DescriptorIndexOptions& options, WordRowFormat format, int cols)
      : stored_bytes_(WordRowBytes(format, cols)), tables_(options, cols) {}
  size_t size() const override { return rows_.size(); }
  bool Contains(WordId word) const override { return rows_.count(word) != 0; }
  const uint8_t* StoredRow(WordId word) const override { return rows_.at(word).get(); }
  void AddStored(WordId word, const uint8_t* row) override {
    if (rows_.empty()) ++rebuilds_;  // a first build, as FLANN's kinds count it
    OwnedRow& stored = rows_.emplace(word, CopyRow(row, stored_bytes_)).first->second;
    tables_.Add(word, stored.get());
  }
  bool Remove(WordId word) override {
    auto it = rows_.find(word);
    if (it == rows_.end()) return false;
    tables_.Remove(word, it->second.get());
    rows_.erase(it);
    return true;
  }
  void SearchTwo(const uint8_t* query, std::vector<WordNeighbour>* out) const override {
    if (!rows_.empty()) tables_.SearchTwo(query, out);
  }
  void Rebuild() override {  // the tables are always up to date
    if (!rows_.empty()) ++rebuilds_;
  }
  int rebuild_count() const override { return rebuilds_; }
  size_t MemoryBytes() const override {
    const size_t n = rows_.size();
    return n * (stored_bytes_ + sizeof(OwnedRow) + sizeof(WordId) + 2 * sizeof(void*) + 16) +
           tables_.MemoryBytes();  // + bucket entries: (word, row) per table
  }

 private:
  size_t stored_bytes_;
  LshTables tables_;
  std::unordered_map<WordId, OwnedRow> rows_;
  int rebuilds_ = 0;
};

// hierarchical: FLANN's hierarchical clustering over whole-row Hamming.
class HierarchicalBackend : public IndexBackend {
 public:
  HierarchicalBackend(const DescriptorIndexOptions& options, WordRowFormat format, int cols)
      : options_(options), cols_(cols), stored_bytes_(WordRowBytes(format, cols)) {}
  size_t size() const override { return rows_.size(); }
  bool Contains(WordId word) const override { return rows_.count(word) != 0; }
  const uint8_t* StoredRow(WordId word) const override { return rows_.at(word).row.get(); }
  void AddStored(WordId word, const uint8_t* data) override {
    Row row{CopyRow(data, stored_bytes_), flann_to_word_.size()};
    flann_to_word_.push_back(word);
    AddToFlann(row.row.get());
    rows_.emplace(word, std::move(row));
  }
  bool Remove(WordId word) override {
    auto it = rows_.find(word);
    if (it == rows_.end()) return false;
    flann_->RemoveRow(it->second.flann_id);
    flann_to_word_[it->second.flann_id] = kNoWord;
    graveyard_.push_back(std::move(it->second.row));  // FLANN may still read it until a rebuild
    rows_.erase(it);
    if (rows_.empty()) Reset();
    return true;
  }
  void SearchTwo(const uint8_t* query, std::vector<WordNeighbour>* out) const override {
    if (rows_.empty()) return;
    size_t ids[kNeighbours];
    float dists[kNeighbours];
    const int k = static_cast<int>(std::min<size_t>(kNeighbours, rows_.size()));
    const int found = flann_->Knn(query, k, options_.checks, ids, dists);
    for (int i = 0; i < found && i < k; ++i) {
      if (ids[i] >= flann_to_word_.size()) continue;  // FLANN marks "none" with -1
      const WordId w = flann_to_word_[ids[i]];
      if (w == kNoWord) continue;
      out->push_back({w, dists[i]});
    }
  }
  void Rebuild() override {
    if (flann_ == nullptr) return;
    flann_->BuildNow();
    AfterBuild(rows_.size());
  }
  int rebuild_count() const override { return rebuilds_; }
  size_t MemoryBytes() const override {
    const size_t n = rows_.size() + graveyard_.size();
    // Own rows and hash nodes, then FLANN: a row pointer and an id per row and
    // an (index, pointer) pair per row per tree.
    return n * (stored_bytes_ + sizeof(Row) + 2 * sizeof(void*) + 16) +
           flann_to_word_.capacity() * sizeof(WordId) + n * (sizeof(void*) + sizeof(size_t)) +
           n * options_.hierarchical_trees * 16;
  }

 private:
  struct Row {
    OwnedRow row;
    size_t flann_id = 0;
  };

  void AddToFlann(const void* row) {
    // The row being added is not in rows_ yet, hence the + 1 below.
    if (flann_ == nullptr) {
      flann_ = std::make_unique<FlannHolderT<WholeRowHamming>>(
          flann::HierarchicalClusteringIndexParams(options_.hierarchical_branching,
                                                   flann::FLANN_CENTERS_RANDOM,
                                                   options_.hierarchical_trees,
                                                   options_.hierarchical_leaf_size),
          cols_, row, options_.seed);
      AfterBuild(rows_.size() + 1);
      return;
    }
    ++flann_rows_;
    // Mirrors FLANN's own test in addPoints (removed rows count until a build).
    const bool rebuilds = size_at_build_ * options_.rebalancing_factor < flann_rows_;
    flann_->AddRow(row, static_cast<float>(options_.rebalancing_factor));
    if (rebuilds) AfterBuild(rows_.size() + 1);
  }
  void AfterBuild(size_t live_rows) {
    ++rebuilds_;
    size_at_build_ = live_rows;
    flann_rows_ = live_rows;
    graveyard_.clear();
  }
  // The last word left: drop FLANN entirely; the next Add starts a new index.
  void Reset() {
    flann_.reset();
    graveyard_.clear();
    flann_to_word_.clear();
    size_at_build_ = 0;
    flann_rows_ = 0;
  }

  DescriptorIndexOptions options_;
  int cols_;
  size_t stored_bytes_;
  std::unordered_map<WordId, Row> rows_;
  std::vector<OwnedRow> graveyard_;
  std::vector<WordId> flann_to_word_;  // FLANN id (insertion order) -> word, kNoWord once removed
  std::unique_ptr<FlannHolder> flann_;
  size_t size_at_build_ = 0;
  size_t flann_rows_ = 0;  // rows FLANN holds, removed-but-not-yet-cleaned included
  int rebuilds_ = 0;
};

std::unique_ptr<IndexBackend> MakeIndexBackend(const DescriptorIndexOptions& options, IndexKind kind,
                                               WordRowFormat format, int cols) {
  switch (kind) {
    case IndexKind::kKdTree:
    case IndexKind::kBitKdTree: return std::make_unique<ForestBackend>(options, format, cols);
    case IndexKind::kLsh: return std::make_unique<LshBackend>(options, format, cols);
    case IndexKind::kHierarchical: return std::make_unique<HierarchicalBackend>(options, format, cols);
    case IndexKind::kLinear: return std::make_unique<LinearBackend>(options, format, cols);
  }
  SLAM_CHECK_MSG(false, "unknown index kind");
  return nullptr;
}

}  // namespace

// The row format (extracted rows encoded into stored ones) over one
// IndexBackend of the configured kind.
class DescriptorIndex::Backend {
 public:
  Backend(const DescriptorIndexOptions& options, DescriptorKind kind, int cols)
      : cols_(cols),
        index_kind_(kind == DescriptorKind::kFloat ? options.float_kind : options.binary_kind),
        format_(WordRowFormatFor(kind, options.float_storage)),
        row_bytes_(QueryRowBytes(format_, cols)),
        stored_bytes_(WordRowBytes(format_, cols)),
        encoded_(stored_bytes_),
        index_(MakeIndexBackend(options, index_kind_, format_, cols)) {}

  IndexKind index_kind() const { return index_kind_; }
  size_t row_bytes() const { return row_bytes_; }
  WordRowFormat format() const { return format_; }
  size_t stored_row_bytes() const { return stored_bytes_; }
  IndexBackend& index() { return *index_; }
  const IndexBackend& index() const { return *index_; }

  void Add(WordId word, const uint8_t* extracted) {
    if (format_ != WordRowFormat::kQuantized8) {  // stored as extracted
      AddStored(word, extracted);
      return;
    }
    SLAM_THROW_IF_NOT(InputError, EncodeWordRow(format_, extracted, cols_, encoded_.data()))
        << "DescriptorIndex: word " << word << " has a non-finite descriptor value";
    AddStored(word, encoded_.data());
  }
  void AddStored(WordId word, const uint8_t* stored) {
    SLAM_CHECK(word > 0 && !index_->Contains(word));
    index_->AddStored(word, stored);
  }
  void Search(const uint8_t* queries, int n, std::vector<std::vector<WordNeighbour>>* out) const {
    out->assign(n, {});
    for (int q = 0; q < n; ++q) index_->SearchTwo(queries + q * row_bytes_, &(*out)[q]);
  }
  bool RestoreState(const uint8_t* state, size_t size, const std::vector<WordId>& ids,
                    const uint8_t* rows, std::string* problem) {
    if (!index_->CanSaveState()) {
      *problem = "this index kind (" + std::string(IndexKindName(index_kind_)) +
                 ") is not restored from a stored state";
      return false;
    }
    return index_->RestoreState(state, size, ids, rows, problem);
  }

 private:
  int cols_;
  IndexKind index_kind_;
  WordRowFormat format_;
  size_t row_bytes_;     // extracted rows (queries)
  size_t stored_bytes_;  // stored rows
  std::vector<uint8_t> encoded_;  // scratch: one row being encoded
  std::unique_ptr<IndexBackend> index_;
};

DescriptorIndex::DescriptorIndex(const DescriptorIndexOptions& options, DescriptorKind kind,
                                 int cols)
    : kind_(kind), cols_(cols) {
  options.Check();
  SLAM_THROW_IF_NOT(InputError, cols > 0) << "DescriptorIndex: descriptor width must be > 0";
  backend_ = std::make_unique<Backend>(options, kind, cols);
}
DescriptorIndex::~DescriptorIndex() = default;

size_t DescriptorIndex::row_bytes() const { return backend_->row_bytes(); }
WordRowFormat DescriptorIndex::format() const { return backend_->format(); }
size_t DescriptorIndex::stored_row_bytes() const { return backend_->stored_row_bytes(); }
IndexKind DescriptorIndex::index_kind() const { return backend_->index_kind(); }
void DescriptorIndex::Add(WordId word, const uint8_t* row) { backend_->Add(word, row); }
void DescriptorIndex::AddStored(WordId word, const uint8_t* stored_row) {
  backend_->AddStored(word, stored_row);
}
bool DescriptorIndex::Remove(WordId word) { return backend_->index().Remove(word); }
bool DescriptorIndex::Contains(WordId word) const { return backend_->index().Contains(word); }
const uint8_t* DescriptorIndex::StoredRow(WordId word) const {
  return backend_->index().StoredRow(word);
}
void DescriptorIndex::SearchTwoNearest(const uint8_t* queries, int rows,
                                       std::vector<std::vector<WordNeighbour>>* out) const {
  backend_->Search(queries, rows, out);
}
void DescriptorIndex::Rebuild() { backend_->index().Rebuild(); }
size_t DescriptorIndex::size() const { return backend_->index().size(); }
int DescriptorIndex::rebuild_count() const { return backend_->index().rebuild_count(); }
size_t DescriptorIndex::MemoryBytes() const { return backend_->index().MemoryBytes(); }

void DescriptorIndex::Compact() { backend_->index().Compact(); }

void DescriptorIndex::ReserveIds(WordId max_id) { backend_->index().ReserveIds(max_id); }

namespace {
constexpr uint32_t kIndexStateMagic = 0x31584944;  // "DIX1"
}  // namespace

bool DescriptorIndex::CanSaveState() const { return backend_->index().CanSaveState(); }

std::vector<uint8_t> DescriptorIndex::SaveState() const {
  std::vector<uint8_t> state;
  if (!CanSaveState()) return state;
  ByteWriter w(&state);
  w.Put(kIndexStateMagic);
  // The row format and width are part of the forest's own shape check.
  w.Put<int32_t>(static_cast<int32_t>(index_kind()));
  w.Put<int32_t>(static_cast<int32_t>(kind_));
  backend_->index().AppendState(&state);
  return state;
}

bool DescriptorIndex::RestoreState(const std::vector<uint8_t>& state,
                                   const std::vector<WordId>& ids, const uint8_t* rows,
                                   std::string* problem) {
  SLAM_CHECK(problem != nullptr);
  ByteReader r(state.data(), state.size());
  uint32_t magic = 0;
  int32_t index_kind = 0, kind = 0;
  if (!r.Get(&magic) || magic != kIndexStateMagic || !r.Get(&index_kind) || !r.Get(&kind)) {
    *problem = "not a stored descriptor index";
    return false;
  }
  if (index_kind != static_cast<int32_t>(this->index_kind()) ||
      kind != static_cast<int32_t>(kind_)) {
    *problem = std::string("the stored index is of another kind (this run uses ") +
               IndexKindName(this->index_kind()) + ")";
    return false;
  }
  const size_t header = state.size() - r.remaining();
  return backend_->RestoreState(state.data() + header, r.remaining(), ids, rows, problem);
}

}  // namespace duskmap
