#include "slam/vocabulary/word_slots.h"

namespace duskmap {

void WordSlots::Set(WordId id, uint32_t slot) {
  SLAM_CHECK(id > 0 && id <= kMaxWordId && slot != kNone);
  const size_t i = static_cast<size_t>(id);
  if (packed_) {
    const size_t rank = PackedRank(i);
    if (rank != kAbsentRank) {
      if (table_[rank] == kNone) ++size_;
      table_[rank] = slot;
      return;
    }
    Unpack();
  }
  if (i >= table_.size()) {
    // Doubling keeps appends of increasing ids amortised O(1).
    const size_t wanted = i + 1;
    if (wanted > table_.capacity()) table_.reserve(std::max(wanted, 2 * table_.capacity()));
    table_.resize(wanted, kNone);
  }
  if (table_[i] == kNone) ++size_;
  table_[i] = slot;
}

void WordSlots::Reserve(WordId max_id) {
  if (max_id <= 0 || max_id > kMaxWordId) return;
  if (packed_) Unpack();
  table_.reserve(static_cast<size_t>(max_id) + 1);
}

bool WordSlots::Erase(WordId id) {
  if (id <= 0) return false;
  const size_t i = static_cast<size_t>(id);
  size_t at = i;
  if (packed_) {
    at = PackedRank(i);
    if (at == kAbsentRank) return false;
  } else if (i >= table_.size()) {
    return false;
  }
  if (table_[at] == kNone) return false;
  table_[at] = kNone;
  --size_;
  return true;
}

void WordSlots::Clear() {
  table_.clear();
  table_.shrink_to_fit();
  bits_.clear();
  bits_.shrink_to_fit();
  ranks_.clear();
  ranks_.shrink_to_fit();
  packed_ = false;
  size_ = 0;
}

void WordSlots::Pack() {
  if (packed_) return;
  // The largest id present bounds the bitmap.
  size_t end = table_.size();
  while (end > 0 && table_[end - 1] == kNone) --end;
  const size_t words = (end + 63) / 64;
  const size_t packed_bytes =
      words * (sizeof(uint64_t) + sizeof(uint32_t)) + size_ * sizeof(uint32_t);
  if (packed_bytes >= table_.capacity() * sizeof(uint32_t)) return;
  std::vector<uint64_t> bits(words, 0);
  std::vector<uint32_t> ranks(words, 0);
  std::vector<uint32_t> slots;
  slots.reserve(size_);
  for (size_t w = 0; w < words; ++w) {
    ranks[w] = static_cast<uint32_t>(slots.size());
    const size_t last = std::min(end, (w + 1) * 64);
    for (size_t i = w * 64; i < last; ++i) {
      if (table_[i] == kNone) continue;
      bits[w] |= uint64_t{1} << (i & 63);
      slots.push_back(table_[i]);
    }
  }
  table_.swap(slots);
  bits_.swap(bits);
  ranks_.swap(ranks);
  packed_ = true;
}

void WordSlots::Unpack() {
  if (!packed_) return;
  std::vector<uint32_t> dense(bits_.size() * 64, kNone);
  size_t end = 0;
  ForEach([&dense, &end](WordId id, uint32_t slot) {
    dense[static_cast<size_t>(id)] = slot;
    end = static_cast<size_t>(id) + 1;
  });
  dense.resize(end);
  table_.swap(dense);
  bits_.clear();
  bits_.shrink_to_fit();
  ranks_.clear();
  ranks_.shrink_to_fit();
  packed_ = false;
}

}  // namespace duskmap
