// Read access to words' stored rows by id, for descriptor rows that a map
// node shares with the vocabulary instead of holding a copy
// (map/shared_rows.h). The Vocabulary is one; a map's stored words are
// another (MapWordsRowSource).
#pragma once

#include <cstdint>

#include "slam/vocabulary/word_types.h"

namespace duskmap {

class WordRowSource {
 public:
  virtual ~WordRowSource() = default;
  // The form of every row returned.
  virtual WordRowFormat stored_row_format() const = 0;
  // The stored row of `word` (WordRowBytes(format, cols) bytes), or nullptr
  // when the word is absent. Valid until the source changes.
  virtual const uint8_t* FindStoredRow(WordId word) const = 0;
};

}  // namespace duskmap
