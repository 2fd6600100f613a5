// The map's vocabulary as a VocabularySnapshot and back: the words (ids,
// descriptors, next id) and each node's word counts and n_j, so that the
// localizer restores the mapper's vocabulary exactly (as the reference loads
// it from its database) instead of quantizing the node descriptors again.
#pragma once

#include "slam/map/map.h"
#include "slam/vocabulary/vocabulary_snapshot.h"

namespace duskmap {

// The snapshot the map stores, with every node (nodes without words, e.g.
// bad signatures, too). Throws InputError when a node's counts and words
// differ in size; Vocabulary::Import checks the rest (words referenced but not
// stored, and the reverse).
VocabularySnapshot MapVocabularySnapshot(const Map& map);
// The same with the words given apart (a map loaded without its words).
VocabularySnapshot MapVocabularySnapshot(const Map& map, const MapWords& words);

// Stores the snapshot in the map: its words, and every node's word counts and
// n_j (nodes the snapshot does not list get no words and n_j = 0). Throws
// InputError when the snapshot names a node the map does not have.
void SetMapVocabulary(const VocabularySnapshot& snapshot, Map* map);

}  // namespace duskmap
