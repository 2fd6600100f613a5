#include "slam/map/shared_rows.h"

#include <algorithm>
#include <cstring>
#include <exception>
#include <future>
#include <functional>
#include <string_view>
#include <utility>
#include <vector>

#include "slam/core/check.h"

namespace duskmap {
namespace {

uint64_t RowHash(const uint8_t* row, size_t bytes) {
  return std::hash<std::string_view>()(
      std::string_view(reinterpret_cast<const char*>(row), bytes));
}

// Every word's row in an open-addressing table keyed by the row's hash (one
// cache miss per lookup; a node map holds a million rows). Words are inserted
// in id order and probed in insertion order, so of two words with the same
// bytes the first is found. Only read once built: threads share it.
class WordRowTable {
 public:
  WordRowTable(const MapWords& words, size_t row_bytes) : words_(words), row_bytes_(row_bytes) {
    size_t slots = 1;
    while (slots < 2 * words.ids.size()) slots <<= 1;
    mask_ = slots - 1;
    table_.resize(slots);
    for (int r = 0; r < static_cast<int>(words.ids.size()); ++r) {
      const uint64_t hash = RowHash(words.descriptors.ptr(r), row_bytes_);
      size_t at = hash & mask_;
      while (table_[at].row >= 0) at = (at + 1) & mask_;
      table_[at] = {hash, r};
    }
  }

  // The row index of the first word whose bytes are `row`'s; -1 when none.
  int Find(const uint8_t* row) const {
    const uint64_t hash = RowHash(row, row_bytes_);
    for (size_t at = hash & mask_; table_[at].row >= 0; at = (at + 1) & mask_) {
      if (table_[at].hash == hash &&
          std::memcmp(words_.descriptors.ptr(table_[at].row), row, row_bytes_) == 0) {
        return table_[at].row;
      }
    }
    return -1;
  }

 private:
  struct Slot {
    uint64_t hash = 0;
    int32_t row = -1;  // -1: empty
  };
  const MapWords& words_;
  size_t row_bytes_;
  size_t mask_ = 0;
  std::vector<Slot> table_;
};

}  // namespace

MapWordsRowSource::MapWordsRowSource(const MapWords& words, WordRowFormat format)
    : words_(words), format_(format) {
  SLAM_CHECK(words.descriptors.rows == static_cast<int>(words.ids.size()));
  if (!words.ids.empty() && words.ids.front() > 0 &&
      static_cast<size_t>(words.ids.back()) <= 4 * words.ids.size() + 1024) {
    row_of_id_.assign(static_cast<size_t>(words.ids.back()) + 1, -1);
    for (size_t r = 0; r < words.ids.size(); ++r) row_of_id_[words.ids[r]] = static_cast<int32_t>(r);
  }
}

const uint8_t* MapWordsRowSource::FindStoredRow(WordId word) const {
  if (!row_of_id_.empty()) {
    if (word <= 0 || static_cast<size_t>(word) >= row_of_id_.size() || row_of_id_[word] < 0) {
      return nullptr;
    }
    return words_.descriptors.ptr(row_of_id_[word]);
  }
  auto it = std::lower_bound(words_.ids.begin(), words_.ids.end(), word);
  if (it == words_.ids.end() || *it != word) return nullptr;
  return words_.descriptors.ptr(static_cast<int>(it - words_.ids.begin()));
}

SharedRowsSummary ShareNodeRowsWithWords(const MapWords& words, Map* map) {
  SharedRowsSummary summary;
  const MapMetadata& meta = map->metadata();
  const WordRowFormat format = WordRowFormatFor(meta.descriptor_kind, meta.word_storage);
  const size_t row_bytes = WordRowBytes(format, meta.descriptor_cols);
  for (const auto& [id, node] : map->nodes()) {
    summary.rows += node.features.size();
    summary.bytes_before += node.features.DescriptorMemoryBytes();
  }
  summary.bytes_after = summary.bytes_before;
  if (words.ids.empty() || meta.descriptor_cols <= 0) return summary;
  const size_t word_row_bytes = words.descriptors.cols * words.descriptors.elemSize();
  SLAM_THROW_IF_NOT(InputError, words.descriptors.isContinuous() && word_row_bytes == row_bytes)
      << "ShareNodeRowsWithWords: word rows of " << word_row_bytes
      << " bytes, the map's format needs " << row_bytes;
  const MapWordsRowSource source(words, format);
  const WordRowTable table(words, row_bytes);
  // Nodes are independent: two threads share them out (the lookup table and
  // the words are only read), each node's result the same either way.
  std::vector<std::pair<NodeId, CompactFeatures*>> nodes;
  for (const auto& [id, unused] : map->nodes()) nodes.push_back({id, &map->mutable_node(id).features});
  auto share = [&](size_t begin, size_t end) {
    std::vector<uint8_t> row(row_bytes);
    std::vector<WordId> row_words;
    for (size_t n = begin; n < end; ++n) {
      CompactFeatures& features = *nodes[n].second;
      SLAM_THROW_IF_NOT(InputError, !features.has_shared_rows())
          << "ShareNodeRowsWithWords: node " << nodes[n].first << " already shares rows";
      row_words.assign(features.size(), kNoWord);
      bool any = false;
      for (size_t i = 0; i < features.size(); ++i) {
        if (!features.RowAsStoredWord(i, format, row.data())) break;  // no word can hold it
        const int found = table.Find(row.data());
        if (found >= 0) {
          row_words[i] = words.ids[found];
          any = true;
        }
      }
      if (any) features.ShareRowsWithWords(row_words, source);
    }
  };
  const size_t half = nodes.size() / 2;
  std::future<void> second = std::async(std::launch::async, share, half, nodes.size());
  std::exception_ptr first_error;
  try {
    share(0, half);
  } catch (...) {
    first_error = std::current_exception();
  }
  second.get();
  if (first_error) std::rethrow_exception(first_error);
  summary.bytes_after = 0;
  for (const auto& [id, features] : nodes) {
    summary.shared_rows += features->num_shared_rows();
    summary.bytes_after += features->DescriptorMemoryBytes();
  }
  return summary;
}

}  // namespace duskmap
