// Word id -> 32-bit slot. Word ids are positive, increase in creation order
// and are never reused. Two forms:
//  - dense, while the vocabulary grows: a table indexed by the id itself,
//    4 bytes per id up to the largest, where a hash map costs a heap node
//    (~40 bytes with malloc's rounding) and a bucket per live word;
//  - packed (Pack), for a vocabulary that is searched rather than grown (an
//    imported map): a bitmap of the ids present with the count of set bits
//    before each 64-bit word, and the slots in id order. 1.5 bits per id up
//    to the largest plus 4 bytes per live word. A merged multi-session map
//    keeps a tenth of the word ids it ever created (the 48-session lifelong
//    map: 238,204 of 2,579,855), so there the dense table costs 10.3 MB and
//    the packed one 1.4 MB.
// Setting an id the packed form does not hold turns it dense again.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "slam/core/check.h"
#include "slam/vocabulary/word_types.h"

namespace duskmap {

// Largest word id a vocabulary accepts: its tables grow with the largest id,
// so a corrupted map naming word 2,000,000,000 must not ask for 8 GB. 2^27
// words is 335,000 nodes of 400 words, far beyond a multi-session map.
constexpr WordId kMaxWordId = WordId{1} << 27;

class WordSlots {
 public:
  static constexpr uint32_t kNone = ~0u;

  uint32_t Find(WordId id) const {
    if (id <= 0) return kNone;
    const size_t i = static_cast<size_t>(id);
    if (!packed_) return i < table_.size() ? table_[i] : kNone;
    const size_t rank = PackedRank(i);
    return rank == kAbsentRank ? kNone : table_[rank];
  }
  bool Contains(WordId id) const { return Find(id) != kNone; }
  size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  bool packed() const { return packed_; }

  // Sets (or replaces) the slot of `id` (0 < id <= kMaxWordId, slot != kNone).
  void Set(WordId id, uint32_t slot);
  // Reserves the dense table for ids up to `max_id` (an import knows its last id).
  void Reserve(WordId max_id);
  // False when absent.
  bool Erase(WordId id);
  void Clear();
  // Converts to the packed form when it takes fewer bytes than the dense one.
  // Lookups are unchanged; the next Set of an id not held makes it dense again.
  void Pack();
  // Calls f(id, slot) for every id present, in increasing id order.
  template <typename F>
  void ForEach(F f) const {
    if (!packed_) {
      for (size_t id = 1; id < table_.size(); ++id) {
        if (table_[id] != kNone) f(static_cast<WordId>(id), table_[id]);
      }
      return;
    }
    size_t rank = 0;
    for (size_t w = 0; w < bits_.size(); ++w) {
      for (uint64_t word = bits_[w]; word != 0; word &= word - 1, ++rank) {
        if (table_[rank] == kNone) continue;  // erased since packing
        f(static_cast<WordId>(w * 64 + static_cast<size_t>(__builtin_ctzll(word))), table_[rank]);
      }
    }
  }
  size_t MemoryBytes() const {
    return table_.capacity() * sizeof(uint32_t) + bits_.capacity() * sizeof(uint64_t) +
           ranks_.capacity() * sizeof(uint32_t);
  }

 private:
  static constexpr size_t kAbsentRank = ~size_t{0};
  // Position in table_ of id i in the packed form, kAbsentRank when its bit is clear.
  size_t PackedRank(size_t i) const {
    const size_t w = i >> 6;
    if (w >= bits_.size()) return kAbsentRank;
    const uint64_t bit = uint64_t{1} << (i & 63);
    if ((bits_[w] & bit) == 0) return kAbsentRank;
    return ranks_[w] + static_cast<size_t>(__builtin_popcountll(bits_[w] & (bit - 1)));
  }
  // Back to the dense form, every present id kept.
  void Unpack();

  // Dense: slot by id (kNone = absent). Packed: slot by rank (kNone = erased
  // since packing).
  std::vector<uint32_t> table_;
  std::vector<uint64_t> bits_;   // packed only: id i present when bit i is set
  std::vector<uint32_t> ranks_;  // packed only: set bits in bits_[0, w)
  bool packed_ = false;
  size_t size_ = 0;
};

}  // namespace duskmap
