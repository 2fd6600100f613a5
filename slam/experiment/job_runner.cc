#include "slam/experiment/job_runner.h"

#include <algorithm>
#include <condition_variable>
#include <mutex>
#include <set>
#include <system_error>
#include <thread>

#include "slam/core/check.h"
#include "slam/core/timer.h"

namespace duskmap {
namespace fs = std::filesystem;
namespace {

enum class State { kPending, kRunning, kDone, kFailed };

// Shared scheduling state, guarded by `mutex`.
struct Scheduler {
  const ExperimentPlan& plan;
  std::vector<State> states;
  std::map<std::string, size_t> index_of;
  std::mutex mutex;
  std::condition_variable changed;
  JobRunSummary summary;
  JobRunProgress progress;

  explicit Scheduler(const ExperimentPlan& p) : plan(p), states(p.jobs.size(), State::kPending) {
    for (size_t i = 0; i < p.jobs.size(); ++i) index_of[p.jobs[i].id] = i;
  }

  State DependencyState(const Job& job) const {
    State worst = State::kDone;
    for (const std::string& dependency : job.depends_on) {
      const auto it = index_of.find(dependency);
      SLAM_CHECK_MSG(it != index_of.end(), "job " + job.id + " depends on unknown " + dependency);
      const State state = states[it->second];
      if (state == State::kFailed) return State::kFailed;
      if (state != State::kDone) worst = State::kPending;
    }
    return worst;
  }

  bool AllFinished() const {
    for (State state : states) {
      if (state == State::kPending || state == State::kRunning) return false;
    }
    return true;
  }

  // Marks failed every pending job whose dependency failed; returns the index
  // of a runnable job, or -1 when none is runnable now.
  long NextRunnable() {
    for (size_t i = 0; i < states.size(); ++i) {
      if (states[i] != State::kPending) continue;
      const State dependencies = DependencyState(plan.jobs[i]);
      if (dependencies == State::kFailed) {
        states[i] = State::kFailed;
        summary.failures.push_back({plan.jobs[i].id, "a job it depends on failed"});
        ++progress.finished;
        ++progress.failed;
        changed.notify_all();
        return NextRunnable();
      }
      if (dependencies == State::kDone) return static_cast<long>(i);
    }
    return -1;
  }
};

void ExecuteOne(const Job& job, JobExecutor& executor, const fs::path& output_dir) {
  const fs::path final_dir = OutputDir(output_dir, job.id);
  const fs::path partial_dir = final_dir.string() + ".partial";
  fs::remove_all(partial_dir);
  fs::create_directories(partial_dir);
  executor.Execute(job, partial_dir);
  fs::remove_all(final_dir);
  fs::rename(partial_dir, final_dir);
}

}  // namespace

void JobRunnerOptions::Check() const {
  SLAM_THROW_IF_NOT(ConfigError, !output_dir.empty()) << "output_dir: must be set";
  SLAM_THROW_IF_NOT(ConfigError, parallel_jobs >= 1)
      << "parallel_jobs: must be >= 1, got " << parallel_jobs;
}

fs::path OutputDir(const fs::path& output_dir, const std::string& job_id) {
  return output_dir / "jobs" / job_id;
}

bool IsJobComplete(const fs::path& output_dir, const std::string& job_id) {
  return fs::is_directory(OutputDir(output_dir, job_id));
}

JobRunSummary RunJobs(const ExperimentPlan& plan, JobExecutor& executor,
                      const JobRunnerOptions& options,
                      const std::function<void(const JobRunProgress&)>& on_progress) {
  options.Check();
  std::error_code error;
  fs::create_directories(options.output_dir, error);
  SLAM_THROW_IF_NOT(InputError, fs::is_directory(options.output_dir))
      << options.output_dir.string() << ": cannot create the results folder";

  const Stopwatch wall;
  Scheduler scheduler(plan);
  scheduler.progress.total = static_cast<int>(plan.jobs.size());
  for (size_t i = 0; i < plan.jobs.size(); ++i) {
    if (options.resume && IsJobComplete(options.output_dir, plan.jobs[i].id)) {
      scheduler.states[i] = State::kDone;
      ++scheduler.summary.resumed;
      ++scheduler.progress.finished;
    }
  }

  auto worker = [&]() {
    std::unique_lock<std::mutex> lock(scheduler.mutex);
    while (true) {
      long next = -1;
      scheduler.changed.wait(lock, [&] {
        next = scheduler.NextRunnable();
        return next >= 0 || scheduler.AllFinished();
      });
      if (next < 0) return;
      const Job& job = plan.jobs[static_cast<size_t>(next)];
      scheduler.states[static_cast<size_t>(next)] = State::kRunning;
      lock.unlock();
      const Stopwatch job_time;
      std::string failure;
      try {
        ExecuteOne(job, executor, options.output_dir);
      } catch (const std::exception& e) {
        failure = e.what();
      }
      lock.lock();
      const double job_s = job_time.ElapsedMs() / 1000.0;
      scheduler.summary.busy_s_by_kind[job.kind] += job_s;
      scheduler.summary.job_wall_s[job.id] = job_s;
      if (failure.empty()) {
        scheduler.states[static_cast<size_t>(next)] = State::kDone;
        ++scheduler.summary.executed;
      } else {
        scheduler.states[static_cast<size_t>(next)] = State::kFailed;
        scheduler.summary.failures.push_back({job.id, failure});
        ++scheduler.progress.failed;
      }
      ++scheduler.progress.finished;
      scheduler.progress.elapsed_s = wall.ElapsedMs() / 1000.0;
      scheduler.progress.last_job_id = job.id;
      if (on_progress) on_progress(scheduler.progress);
      scheduler.changed.notify_all();
    }
  };

  // No more workers than jobs to run; a worker that cannot be started (the
  // system's thread limit) leaves the others to do the work.
  const size_t to_run = plan.jobs.size() - static_cast<size_t>(scheduler.summary.resumed);
  const size_t wanted = std::max<size_t>(
      1, std::min(static_cast<size_t>(options.parallel_jobs), to_run));
  std::vector<std::thread> threads;
  for (size_t i = 0; i < wanted; ++i) {
    try {
      threads.emplace_back(worker);
    } catch (const std::system_error&) {
      if (threads.empty()) throw;
      break;
    }
  }
  for (std::thread& thread : threads) thread.join();
  scheduler.summary.wall_s = wall.ElapsedMs() / 1000.0;
  return scheduler.summary;
}

}  // namespace duskmap
