// Word id -> 32-bit slot through a table indexed by the id itself. Word ids
// are positive, increase in creation order and are never reused, so the
// table is as long as the largest id seen: 4 bytes per id, where a hash map
// costs a heap node (~40 bytes with malloc's rounding) and a bucket per live
// word.
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
    return id > 0 && static_cast<size_t>(id) < table_.size() ? table_[id] : kNone;
  }
  bool Contains(WordId id) const { return Find(id) != kNone; }
  size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }

  // Sets (or replaces) the slot of `id` (0 < id <= kMaxWordId, slot != kNone).
  void Set(WordId id, uint32_t slot) {
    SLAM_CHECK(id > 0 && id <= kMaxWordId && slot != kNone);
    if (static_cast<size_t>(id) >= table_.size()) {
      // Doubling keeps appends of increasing ids amortised O(1).
      const size_t wanted = static_cast<size_t>(id) + 1;
      if (wanted > table_.capacity()) table_.reserve(std::max(wanted, 2 * table_.capacity()));
      table_.resize(wanted, kNone);
    }
    if (table_[id] == kNone) ++size_;
    table_[id] = slot;
  }
  // Reserves the table for ids up to `max_id` (an import knows its last id).
  void Reserve(WordId max_id) {
    if (max_id > 0 && max_id <= kMaxWordId) table_.reserve(static_cast<size_t>(max_id) + 1);
  }
  // False when absent.
  bool Erase(WordId id) {
    if (!Contains(id)) return false;
    table_[id] = kNone;
    --size_;
    return true;
  }
  void Clear() {
    table_.clear();
    table_.shrink_to_fit();
    size_ = 0;
  }
  // Calls f(id, slot) for every id present, in increasing id order.
  template <typename F>
  void ForEach(F f) const {
    for (size_t id = 1; id < table_.size(); ++id) {
      if (table_[id] != kNone) f(static_cast<WordId>(id), table_[id]);
    }
  }
  size_t MemoryBytes() const { return table_.capacity() * sizeof(uint32_t); }

 private:
  std::vector<uint32_t> table_;  // by id; kNone = absent
  size_t size_ = 0;
};

}  // namespace duskmap
