#include "slam/experiment/job_runner.h"

#include <atomic>
#include <fstream>
#include <mutex>
#include <set>

#include <gtest/gtest.h>

#include "slam/core/check.h"
#include "tests/testing/temp_dir.h"

namespace duskmap {
namespace fs = std::filesystem;
namespace {

using testing::ProcessTempDir;

ExperimentPlan SmallPlan() {
  ExperimentOptions options;
  options.dataset_path = "d";
  options.features = {"SI", "OR"};
  options.maps = {ParseMapSpec("1"), ParseMapSpec("1+2")};
  options.localization_sessions = {"A", "B"};
  return PlanExperiment(options, {});
}

// Records the order of execution, checks that dependencies are complete, and
// fails the jobs it is told to.
class RecordingExecutor : public JobExecutor {
 public:
  RecordingExecutor(fs::path output_dir, std::set<std::string> failing)
      : output_dir_(std::move(output_dir)), failing_(std::move(failing)) {}
  void Execute(const Job& job, const fs::path& job_dir) override {
    for (const std::string& dependency : job.depends_on) {
      EXPECT_TRUE(IsJobComplete(output_dir_, dependency)) << job.id << " ran before " << dependency;
    }
    if (failing_.count(job.id)) throw InputError("cannot read " + job.id);
    std::ofstream(job_dir / "result.json") << "{}";
    std::lock_guard<std::mutex> lock(mutex_);
    executed_.push_back(job.id);
  }
  std::vector<std::string> executed() const { return executed_; }

 private:
  fs::path output_dir_;
  std::set<std::string> failing_;
  std::mutex mutex_;
  std::vector<std::string> executed_;
};

TEST(RunJobs, RunsEveryJobOnceInParallelRespectingDependencies) {
  const ExperimentPlan plan = SmallPlan();
  const fs::path dir = ProcessTempDir("job_runner_parallel");
  RecordingExecutor executor(dir, {});
  int progress_calls = 0;
  const JobRunSummary summary = RunJobs(plan, executor, {dir, 2, false},
                                        [&](const JobRunProgress&) { ++progress_calls; });
  EXPECT_TRUE(summary.ok());
  EXPECT_EQ(summary.executed, static_cast<int>(plan.jobs.size()));
  EXPECT_EQ(progress_calls, static_cast<int>(plan.jobs.size()));
  const auto executed = executor.executed();
  EXPECT_EQ(std::set<std::string>(executed.begin(), executed.end()).size(), plan.jobs.size());
  for (const Job& job : plan.jobs) EXPECT_TRUE(IsJobComplete(dir, job.id)) << job.id;
}

TEST(RunJobs, FarMoreWorkersThanJobsRunEveryJobOnce) {
  // --jobs 100000 used to start 100,000 threads and abort when one failed.
  const ExperimentPlan plan = SmallPlan();
  const fs::path dir = ProcessTempDir("job_runner_many_workers");
  RecordingExecutor executor(dir, {});
  const JobRunSummary summary = RunJobs(plan, executor, {dir, 100000, false});
  EXPECT_TRUE(summary.ok());
  EXPECT_EQ(summary.executed, static_cast<int>(plan.jobs.size()));
  // Resumed with every job done: nothing to run, still one clean return.
  const JobRunSummary again = RunJobs(plan, executor, {dir, 100000, true});
  EXPECT_EQ(again.resumed, static_cast<int>(plan.jobs.size()));
  EXPECT_EQ(again.executed, 0);
}

TEST(PlanExperiment, ListsTheLocalizationsOfAMapTogetherAfterTheirDependencies) {
  ExperimentOptions options;
  options.dataset_path = "d";
  options.features = {"SI"};
  options.maps = {ParseMapSpec("1"), ParseMapSpec("1+2"), ParseMapSpec("1|2")};
  options.localization_sessions = {"A", "B"};
  options.consecutive_pairs = {{"1", "2"}};
  const ExperimentPlan plan = PlanExperiment(options, {{"1", 600}, {"2", 630}, {"A", 605}, {"B", 640}});
  std::set<std::string> listed;
  std::string previous_map;
  std::set<std::string> finished_maps;
  for (const Job& job : plan.jobs) {
    for (const std::string& d : job.depends_on) EXPECT_TRUE(listed.count(d)) << job.id << " before " << d;
    listed.insert(job.id);
    if (job.kind != JobKind::kLocalize) continue;
    const std::string& map = job.depends_on.front();
    if (map != previous_map) {
      EXPECT_FALSE(finished_maps.count(map)) << "localizations on " << map << " are split";
      if (!previous_map.empty()) finished_maps.insert(previous_map);
      previous_map = map;
    }
  }
  EXPECT_EQ(listed.size(), plan.jobs.size());
}

TEST(RunJobs, ResumeSkipsFinishedJobsAndRerunsPartialOnes) {
  const ExperimentPlan plan = SmallPlan();
  const fs::path dir = ProcessTempDir("job_runner_resume");
  const std::string failing = "map/SI/1+2";
  {
    RecordingExecutor first(dir, {failing});
    const JobRunSummary summary = RunJobs(plan, first, {dir, 1, false});
    // The map and the two localizations on it fail.
    EXPECT_EQ(summary.failures.size(), 3u);
    EXPECT_EQ(summary.failures.front().job_id, failing);
    EXPECT_NE(summary.failures.front().message.find("cannot read"), std::string::npos);
    EXPECT_FALSE(IsJobComplete(dir, failing));
    EXPECT_TRUE(fs::exists(OutputDir(dir, failing).string() + ".partial"));
  }
  RecordingExecutor second(dir, {});
  const JobRunSummary summary = RunJobs(plan, second, {dir, 2, true});
  EXPECT_TRUE(summary.ok());
  EXPECT_EQ(summary.executed, 3);
  EXPECT_EQ(summary.resumed, static_cast<int>(plan.jobs.size()) - 3);
}

TEST(RunJobs, RejectsInvalidOptions) {
  RecordingExecutor executor("x", {});
  EXPECT_THROW(RunJobs(SmallPlan(), executor, {"", 1, false}), ConfigError);
  EXPECT_THROW(RunJobs(SmallPlan(), executor, {ProcessTempDir("job_runner_bad"), 0, false}), ConfigError);
}

}  // namespace
}  // namespace duskmap
