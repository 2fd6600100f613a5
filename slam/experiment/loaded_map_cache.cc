#include "slam/experiment/loaded_map_cache.h"

#include "slam/core/check.h"
#include "slam/core/timer.h"

namespace duskmap {

LoadedMapCache::LoadedMapCache(size_t capacity) : capacity_(capacity) {
  SLAM_CHECK(capacity >= 1);
}

SharedMap LoadedMapCache::Get(const std::string& path, const MapLoadOptions& options) {
  std::shared_ptr<Entry> entry;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    for (auto it = entries_.begin(); it != entries_.end(); ++it) {
      if ((*it)->path == path) {
        entry = *it;
        entries_.erase(it);
        break;
      }
    }
    if (entry == nullptr) {
      entry = std::make_shared<Entry>();
      entry->path = path;
    }
    entries_.push_front(entry);
    // An evicted map stays alive while a job still holds it.
    while (entries_.size() > capacity_) entries_.pop_back();
  }
  std::lock_guard<std::mutex> lock(entry->mutex);
  SharedMap shared;
  if (entry->loaded != nullptr) {
    shared.loaded = entry->loaded;
    shared.from_cache = true;
    return shared;
  }
  Stopwatch watch;
  try {
    entry->loaded = std::make_shared<const MapAndWords>(LoadMapAndWords(path, options));
  } catch (...) {
    std::lock_guard<std::mutex> list_lock(mutex_);
    entries_.remove(entry);
    throw;
  }
  shared.loaded = entry->loaded;
  shared.load_s = watch.ElapsedMs() / 1000.0;
  return shared;
}

}  // namespace duskmap
