#include "slam/engine/vocabulary_index.h"

#include "slam/core/check.h"
#include "slam/core/timer.h"
#include "slam/map/map_vocabulary.h"
#include "slam/vocabulary/vocabulary.h"

namespace duskmap {

double StoreVocabularyIndex(const EngineOptions& options, Map* map) {
  SLAM_CHECK(map != nullptr);
  Stopwatch watch;
  if (map->words().ids.empty()) {
    map->SetWordIndexState({});
    return 0.0;
  }
  VocabularySnapshot snapshot = MapVocabularySnapshot(*map);
  snapshot.index_state.clear();  // build, as a load without a stored index does
  snapshot.index_state_problem.clear();
  Vocabulary vocabulary(options.LoopClosure().vocabulary);
  vocabulary.Import(snapshot);
  map->SetWordIndexState(vocabulary.SaveIndexState());
  return watch.ElapsedMs() / 1000.0;
}

}  // namespace duskmap
