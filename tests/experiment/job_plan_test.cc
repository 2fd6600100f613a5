#include "slam/experiment/job_plan.h"

#include <set>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "slam/core/check.h"
#include "slam/experiment/run_manifest.h"

namespace duskmap {
namespace {

using ::testing::ElementsAre;

SessionClock PaperClock() {
  SessionClock clock;
  const char* names[] = {"1", "2", "3", "4", "5", "6", "A", "B", "C", "D", "E", "F"};
  const char* times[] = {"16:46", "17:27", "17:54", "18:27", "18:56", "19:35",
                         "16:51", "17:31", "17:58", "18:30", "18:59", "19:42"};
  for (int i = 0; i < 12; ++i) clock[names[i]] = ParseClockMinutes(times[i]);
  return clock;
}

ExperimentOptions SmallOptions() {
  ExperimentOptions options;
  options.dataset_path = "data";
  options.features = {"SI", "OR"};
  for (const char* label : {"1", "6", "1+6", "1-2-3", "1|6"}) {
    options.maps.push_back(ParseMapSpec(label));
  }
  options.localization_sessions = {"A", "F"};
  options.consecutive_pairs = {{"1", "2"}, {"1", "3"}, {"1", "6"}};
  return options;
}

TEST(ParseClockMinutes, ParsesAndRejects) {
  EXPECT_EQ(ParseClockMinutes("16:46"), 16 * 60 + 46);
  EXPECT_THROW(ParseClockMinutes("25:00"), ConfigError);
  EXPECT_THROW(ParseClockMinutes("16h46"), ConfigError);
  EXPECT_THROW(ParseClockMinutes("16:46x"), ConfigError);
}

TEST(PlanExperiment, DependenciesComeFirstAndIdsAreUnique) {
  const ExperimentPlan plan = PlanExperiment(SmallOptions(), PaperClock());
  std::set<std::string> done;
  for (const Job& job : plan.jobs) {
    for (const std::string& dependency : job.depends_on) {
      EXPECT_TRUE(done.count(dependency)) << job.id << " before " << dependency;
    }
    EXPECT_TRUE(done.insert(job.id).second) << "duplicate " << job.id;
  }
}

TEST(PlanExperiment, ClosestInTimeReusesSingleMaps) {
  const ExperimentPlan plan = PlanExperiment(SmallOptions(), PaperClock());
  std::map<std::string, std::string> closest;
  for (const MatrixCell& cell : plan.cells) {
    if (cell.feature == "SI" && cell.row == "1|6") closest[cell.session] = cell.job_id;
  }
  EXPECT_EQ(closest["A"], "localize/SI/1/A");  // 16:51 is closest to 16:46
  EXPECT_EQ(closest["F"], "localize/SI/6/F");  // 19:42 is closest to 19:35
  // No map is built for the "1|6" row itself.
  EXPECT_EQ(plan.FindJob("map/SI/1|6"), nullptr);
}

TEST(PlanExperiment, ExtractionIsSharedAcrossMapsAndMatchers) {
  ExperimentOptions options = SmallOptions();
  options.features = {"SP", "SG"};
  const ExperimentPlan plan = PlanExperiment(options, PaperClock());
  int extract_jobs = 0;
  for (const Job& job : plan.jobs) extract_jobs += job.kind == JobKind::kExtract;
  // Sessions 1, 2, 3, 6, A, F once each: SP and SG share SuperPoint features.
  EXPECT_EQ(extract_jobs, 6);
  EXPECT_NE(plan.FindJob("map/SG/1+6"), nullptr);
  EXPECT_NE(plan.FindJob("map/SP/1+6"), nullptr);
}

// Every job carries its column's setup: the executor never looks it up
// again. SP and SG share one extract job, run with SP's setup (listed first).
TEST(PlanExperiment, JobsCarryTheirFeatureSetup) {
  ExperimentOptions options = SmallOptions();
  options.features = {"SP", "SG", "OR"};
  const ExperimentPlan plan = PlanExperiment(options, PaperClock());
  for (const Job& job : plan.jobs) {
    EXPECT_EQ(job.setup.CacheName(), job.extractor) << job.id;
    if (job.kind == JobKind::kExtract) {
      EXPECT_EQ(job.setup.label, job.extractor == "orb" ? "OR" : "SP") << job.id;
    } else {
      EXPECT_EQ(job.setup.label, job.feature) << job.id;
      EXPECT_EQ(job.setup.matcher, job.feature == "SG" ? "superglue" : "nndr") << job.id;
    }
  }
  EXPECT_EQ(plan.FindJob("extract/superpoint/A")->setup.extractor, "superpoint");
}

TEST(PlanExperiment, ConsecutivePairsGetGapClasses) {
  const ExperimentPlan plan = PlanExperiment(SmallOptions(), PaperClock());
  std::vector<int> classes;
  for (const ConsecutiveCell& cell : plan.consecutive) {
    if (cell.feature == "SI") classes.push_back(cell.gap_class_min);
  }
  EXPECT_THAT(classes, ElementsAre(30, 60, 120));  // 41, 68 and 169 minutes apart
}

TEST(PlanExperiment, MissingClockTimeIsAConfigError) {
  SessionClock clock = PaperClock();
  clock.erase("6");
  EXPECT_THROW(PlanExperiment(SmallOptions(), clock), ConfigError);
}

TEST(SelectShard, ShardsPartitionTheCellsAndKeepDependencies) {
  const ExperimentPlan plan = PlanExperiment(SmallOptions(), PaperClock());
  std::multiset<std::string> cell_jobs;
  for (int index = 0; index < 3; ++index) {
    const ExperimentPlan shard = SelectShard(plan, index, 3);
    std::set<std::string> ids;
    for (const Job& job : shard.jobs) {
      for (const std::string& dependency : job.depends_on) EXPECT_TRUE(ids.count(dependency));
      ids.insert(job.id);
    }
    for (const MatrixCell& cell : shard.cells) cell_jobs.insert(cell.job_id + "@" + cell.row);
  }
  std::multiset<std::string> all;
  for (const MatrixCell& cell : plan.cells) all.insert(cell.job_id + "@" + cell.row);
  EXPECT_EQ(cell_jobs, all);
  EXPECT_THROW(SelectShard(plan, 3, 3), ConfigError);
}

TEST(SessionClockOf, ConfiguredTimesFillInAndOverrideTheDatasets) {
  // A database stores no clock time ("1"); a synthetic session does ("A").
  SessionInfo stored_none;
  stored_none.name = "1";
  SessionInfo stored;
  stored.name = "A";
  stored.clock_time = "16:51";
  EXPECT_EQ(SessionClockOf({stored_none, stored}).count("1"), 0u);
  const SessionClock clock = SessionClockOf({stored_none, stored}, {{"1", "16:46"}, {"A", "17:00"}});
  EXPECT_EQ(clock.at("1"), 16 * 60 + 46);
  EXPECT_EQ(clock.at("A"), 17 * 60);
}

}  // namespace
}  // namespace duskmap
