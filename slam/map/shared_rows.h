// Node descriptor rows shared with the vocabulary's words, for a map loaded
// for localization. A word's stored row is the descriptor of the feature
// that created it, so that feature's node holds the same bytes a second
// time (about one row in three of a night map's nodes: the ones that made
// new words). ShareNodeRowsWithWords finds those rows and replaces each by
// the word's id (CompactFeatures::ShareRowsWithWords); Decode() then reads
// them from the vocabulary the words are imported into. Lossless: decoded
// features are bit for bit those of the unshared map.
#pragma once

#include <cstddef>

#include "slam/map/map.h"
#include "slam/vocabulary/word_row_source.h"

namespace duskmap {

// A map's stored words as a WordRowSource (ids increasing, binary search).
class MapWordsRowSource : public WordRowSource {
 public:
  MapWordsRowSource(const MapWords& words, WordRowFormat format);
  WordRowFormat stored_row_format() const override { return format_; }
  const uint8_t* FindStoredRow(WordId word) const override;

 private:
  const MapWords& words_;
  WordRowFormat format_;
  // Row of each id (-1: none) when ids are dense enough for a table (a map's
  // are: ids are given in creation order and few words are removed);
  // otherwise empty and rows are found by binary search.
  std::vector<int32_t> row_of_id_;
};

struct SharedRowsSummary {
  size_t rows = 0;         // descriptor rows of all nodes
  size_t shared_rows = 0;  // replaced by a word reference
  size_t bytes_before = 0; // CompactFeatures::DescriptorMemoryBytes, summed
  size_t bytes_after = 0;
};

// Shares every node row that equals a word's stored row byte for byte (and
// is in a form the words can hold exactly: see RowAsStoredWord). `words`
// are the map's words (held apart from it, as LoadMapAndWords returns
// them); the nodes must have no shared row yet. The map can then no longer
// be saved (SaveMap refuses it).
SharedRowsSummary ShareNodeRowsWithWords(const MapWords& words, Map* map);

}  // namespace duskmap
