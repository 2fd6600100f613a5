// Runs the jobs of an experiment plan: dependencies first, independent jobs in
// parallel, every job's output in its own folder <output>/<job id>/ that
// appears atomically (written as <job id>.partial, then renamed), so that an
// interrupted run resumes without redoing finished jobs.
#pragma once

#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "slam/experiment/job_plan.h"

namespace duskmap {

// Does the work of one job. Implementations write their outputs into
// `job_dir` and read the outputs of dependencies through `OutputDir`; they
// throw duskmap::Error (or any std::exception) on failure.
class JobExecutor {
 public:
  virtual ~JobExecutor() = default;
  virtual void Execute(const Job& job, const std::filesystem::path& job_dir) = 0;
};

struct JobRunnerOptions {
  std::filesystem::path output_dir;  // results folder (created when absent)
  int parallel_jobs = 1;             // worker threads, >= 1
  bool resume = false;               // skip jobs whose output folder is complete

  void Check() const;
};

// Folder of a finished job's outputs.
std::filesystem::path OutputDir(const std::filesystem::path& output_dir, const std::string& job_id);
// Whether a finished job's outputs exist.
bool IsJobComplete(const std::filesystem::path& output_dir, const std::string& job_id);

struct JobRunProgress {
  int finished = 0;  // executed, resumed or failed so far
  int total = 0;
  int failed = 0;
  double elapsed_s = 0.0;
  std::string last_job_id;
};

struct JobFailure {
  std::string job_id;
  std::string message;  // the executor's error, or the failed dependency
};

struct JobRunSummary {
  int executed = 0;
  int resumed = 0;  // already complete from an earlier run
  std::vector<JobFailure> failures;
  double wall_s = 0.0;
  std::map<JobKind, double> busy_s_by_kind;  // summed job time per kind
  std::map<std::string, double> job_wall_s;  // each executed job's time, by id

  bool ok() const { return failures.empty(); }
};

// Runs every job of `plan`. A job whose dependency failed fails without
// running. `on_progress` (optional) is called after each job, from the thread
// that finished it, serialised by the runner.
JobRunSummary RunJobs(const ExperimentPlan& plan, JobExecutor& executor,
                      const JobRunnerOptions& options,
                      const std::function<void(const JobRunProgress&)>& on_progress = {});

}  // namespace duskmap
