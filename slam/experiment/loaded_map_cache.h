// Maps loaded for localization jobs, shared by the jobs on the same map: the
// runner lists a map's localization jobs together (job_plan.h), so with a
// few maps kept, each map is read from disk about once instead of once per
// job. Each job still builds its own localizer over the shared, read-only
// map, so its results do not depend on which jobs ran before it.
#pragma once

#include <cstddef>
#include <list>
#include <memory>
#include <mutex>
#include <string>

#include "slam/map/map_store.h"

namespace duskmap {

struct SharedMap {
  std::shared_ptr<const MapAndWords> loaded;
  bool from_cache = false;  // loaded earlier (by this or another job)
  double load_s = 0.0;      // time this caller spent loading (0 from the cache)
};

class LoadedMapCache {
 public:
  // `capacity`: maps kept (least recently used goes first), >= 1.
  explicit LoadedMapCache(size_t capacity);

  // The map at `path` loaded with `options` (the same options for every
  // caller of one path). Concurrent callers of one path wait for one load;
  // other paths load in parallel. Throws what LoadMapAndWords throws (and
  // keeps nothing for that path).
  SharedMap Get(const std::string& path, const MapLoadOptions& options);

 private:
  struct Entry {
    std::string path;
    std::mutex mutex;  // held while loading
    std::shared_ptr<const MapAndWords> loaded;
  };
  size_t capacity_;
  std::mutex mutex_;
  std::list<std::shared_ptr<Entry>> entries_;  // most recently used first
};

}  // namespace duskmap
