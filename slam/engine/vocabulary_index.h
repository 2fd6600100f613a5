// The vocabulary index a map stores for its localizers: the NN index that
// Vocabulary::Import builds from the map's words with the localizer's
// options, saved as bytes (MapWords::index_state) so that opening the map
// restores it instead of dividing the KD-trees again. Restored or rebuilt,
// the index is the same, byte for byte, so results do not depend on it.
#pragma once

#include "slam/engine/engine_options.h"
#include "slam/map/map.h"

namespace duskmap {

// Builds the index from the map's words as a Localizer with `options` would
// and stores it in the map (nothing for a map without words, or for index
// kinds that are not stored). Returns the seconds it took.
double StoreVocabularyIndex(const EngineOptions& options, Map* map);

}  // namespace duskmap
