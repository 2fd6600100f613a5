#include "slam/map/shared_rows.h"

#include <algorithm>
#include <cstring>
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

}  // namespace

MapWordsRowSource::MapWordsRowSource(const MapWords& words, WordRowFormat format)
    : words_(words), format_(format) {
  SLAM_CHECK(words.descriptors.rows == static_cast<int>(words.ids.size()));
}

const uint8_t* MapWordsRowSource::FindStoredRow(WordId word) const {
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
  // (hash, row) of every word, sorted: equal rows are found by hash, then
  // compared byte for byte.
  std::vector<std::pair<uint64_t, int>> by_hash(words.ids.size());
  for (int r = 0; r < static_cast<int>(words.ids.size()); ++r) {
    by_hash[r] = {RowHash(words.descriptors.ptr(r), row_bytes), r};
  }
  std::sort(by_hash.begin(), by_hash.end());
  std::vector<uint8_t> row(row_bytes);
  std::vector<WordId> row_words;
  summary.bytes_after = 0;
  for (const auto& [id, unused] : map->nodes()) {
    CompactFeatures& features = map->mutable_node(id).features;
    SLAM_THROW_IF_NOT(InputError, !features.has_shared_rows())
        << "ShareNodeRowsWithWords: node " << id << " already shares rows";
    row_words.assign(features.size(), kNoWord);
    bool any = false;
    for (size_t i = 0; i < features.size(); ++i) {
      if (!features.RowAsStoredWord(i, format, row.data())) break;  // no word can hold it
      const uint64_t hash = RowHash(row.data(), row_bytes);
      auto it = std::lower_bound(by_hash.begin(), by_hash.end(), std::make_pair(hash, -1));
      for (; it != by_hash.end() && it->first == hash; ++it) {
        if (std::memcmp(words.descriptors.ptr(it->second), row.data(), row_bytes) == 0) {
          row_words[i] = words.ids[it->second];
          any = true;
          break;
        }
      }
    }
    if (any) features.ShareRowsWithWords(row_words, source);
    summary.shared_rows += features.num_shared_rows();
    summary.bytes_after += features.DescriptorMemoryBytes();
  }
  return summary;
}

}  // namespace duskmap
