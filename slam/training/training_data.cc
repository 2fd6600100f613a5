#include "slam/training/training_data.h"

#include <algorithm>
#include <exception>
#include <map>
#include <mutex>
#include <thread>

#include "slam/core/timer.h"
#include "slam/synthetic/training_scenes.h"
#include "slam/training/held_out.h"
#include "slam/training/training_pairs.h"

namespace duskmap {
namespace {

// Scenes finished out of order wait here until every scene before them is written.
class OrderedSceneWriter {
 public:
  OrderedSceneWriter(TrainingDataWriter* writer, const std::function<void(const TrainingSceneProgress&)>& progress,
                     int scenes)
      : writer_(writer), progress_(progress), scenes_(scenes) {}

  void Add(TrainingScene scene, ScenePairs pairs) {
    std::lock_guard<std::mutex> lock(mutex_);
    const int index = scene.index;
    done_.emplace(index, std::make_pair(std::move(scene), std::move(pairs)));
    for (auto it = done_.find(next_); it != done_.end(); it = done_.find(next_)) {
      writer_->Append(it->second.first, it->second.second);
      const ScenePairs& p = it->second.second;
      const TrainingSceneRecord& record = writer_->manifest().scenes.back();
      if (progress_) progress_({next_, scenes_, record.split, p.frames, p.image_pairs, p.pairs, p.wall_s});
      done_.erase(it);
      ++next_;
    }
  }

 private:
  std::mutex mutex_;
  TrainingDataWriter* writer_;
  const std::function<void(const TrainingSceneProgress&)>& progress_;
  int scenes_;
  int next_ = 0;
  std::map<int, std::pair<TrainingScene, ScenePairs>> done_;
};

}  // namespace

TrainingDataSummary GenerateTrainingData(const TrainingDataOptions& options, const TrainingDataRunOptions& run,
                                         const std::function<void(const TrainingSceneProgress&)>& progress) {
  options.Check();
  Stopwatch watch;
  const int scenes = options.scenes.scenes;
  // Every scene is checked against the held-out rule before any is rendered.
  for (int i = 0; i < scenes; ++i) CheckHeldOut(MakeTrainingScene(options.scenes, i));
  TrainingDataWriter writer(run.output_path, run.overwrite, options);
  OrderedSceneWriter ordered(&writer, progress, scenes);
  std::mutex next_mutex;
  int next = 0;
  std::exception_ptr error;
  auto worker = [&] {
    for (;;) {
      int index = 0;
      {
        std::lock_guard<std::mutex> lock(next_mutex);
        if (error || next >= scenes) return;
        index = next++;
      }
      try {
        TrainingScene scene = MakeTrainingScene(options.scenes, index);
        ScenePairs pairs = RenderScenePairs(scene, options);
        ordered.Add(std::move(scene), std::move(pairs));
      } catch (...) {
        std::lock_guard<std::mutex> lock(next_mutex);
        if (!error) error = std::current_exception();
      }
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < std::min(options.threads, scenes); ++t) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
  if (error) std::rethrow_exception(error);
  TrainingDataSummary summary;
  summary.manifest = writer.Finish();
  summary.output_path = writer.final_path();
  summary.wall_s = watch.ElapsedMs() / 1000.0;
  return summary;
}

}  // namespace duskmap
