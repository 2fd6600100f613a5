#include "slam/experiment/job_plan.h"

#include <algorithm>
#include <cstdlib>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "slam/core/check.h"

namespace duskmap {
namespace {

std::string ExtractId(const std::string& extractor, const std::string& session) {
  return "extract/" + extractor + "/" + session;
}
std::string MapId(const std::string& feature, const MapSpec& map) {
  return "map/" + feature + "/" + map.label;
}
std::string LocalizeId(const std::string& feature, const MapSpec& map, const std::string& session) {
  return "localize/" + feature + "/" + map.label + "/" + session;
}

int ClockOf(const SessionClock& clock, const std::string& session, const std::string& why) {
  const auto it = clock.find(session);
  SLAM_THROW_IF_NOT(ConfigError, it != clock.end())
      << "session '" << session << "' has no clock time, needed for " << why;
  return it->second;
}

// Builds the job list while keeping ids unique and dependencies first.
class PlanBuilder {
 public:
  explicit PlanBuilder(ExperimentPlan* plan) : plan_(plan) {}

  void AddExtract(const FeatureSetup& feature, const std::string& session) {
    Job job;
    job.kind = JobKind::kExtract;
    job.id = ExtractId(feature.CacheName(), session);
    job.extractor = feature.CacheName();
    job.setup = feature;
    job.session = session;
    Add(std::move(job));
  }
  void AddMap(const FeatureSetup& feature, const MapSpec& map) {
    Job job;
    job.kind = JobKind::kBuildMap;
    job.id = MapId(feature.label, map);
    job.feature = feature.label;
    job.extractor = feature.CacheName();
    job.setup = feature;
    job.map = map;
    for (const std::string& session : map.sessions) {
      AddExtract(feature, session);
      job.depends_on.push_back(ExtractId(feature.CacheName(), session));
    }
    Add(std::move(job));
  }
  std::string AddLocalize(const FeatureSetup& feature, const MapSpec& map,
                          const std::string& session) {
    AddMap(feature, map);
    AddExtract(feature, session);
    Job job;
    job.kind = JobKind::kLocalize;
    job.id = LocalizeId(feature.label, map, session);
    job.feature = feature.label;
    job.extractor = feature.CacheName();
    job.setup = feature;
    job.map = map;
    job.session = session;
    job.depends_on = {MapId(feature.label, map), ExtractId(feature.CacheName(), session)};
    const std::string id = job.id;
    Add(std::move(job));
    return id;
  }

 private:
  void Add(Job job) {
    if (!ids_.insert(job.id).second) return;
    plan_->jobs.push_back(std::move(job));
  }
  ExperimentPlan* plan_;
  std::set<std::string> ids_;
};

std::string ClosestSession(const MapSpec& map, const std::string& session,
                           const SessionClock& clock) {
  const int when = ClockOf(clock, session, "map '" + map.label + "'");
  std::string best;
  int best_gap = std::numeric_limits<int>::max();
  for (const std::string& candidate : map.sessions) {
    const int gap = std::abs(ClockOf(clock, candidate, "map '" + map.label + "'") - when);
    if (gap < best_gap) {  // ties keep the earlier-listed session
      best_gap = gap;
      best = candidate;
    }
  }
  return best;
}

int NearestClass(int gap_min, const std::vector<int>& classes) {
  int best = classes.front();
  for (int c : classes) {
    if (std::abs(c - gap_min) < std::abs(best - gap_min)) best = c;
  }
  return best;
}

}  // namespace

const char* JobKindName(JobKind kind) {
  switch (kind) {
    case JobKind::kExtract: return "extract";
    case JobKind::kBuildMap: return "map";
    case JobKind::kLocalize: return "localize";
  }
  return "unknown";
}

const Job* ExperimentPlan::FindJob(const std::string& id) const {
  for (const Job& job : jobs) {
    if (job.id == id) return &job;
  }
  return nullptr;
}

namespace {

// Moves the localization jobs of each map next to each other, where the last
// of them was: every dependency of the group is then still listed before it,
// and the runner (which starts the first runnable job in list order) runs a
// map's localizations one after the other, sharing its loaded copy.
void GroupLocalizationsByMap(ExperimentPlan* plan) {
  std::map<std::string, size_t> last_of_map;
  for (size_t i = 0; i < plan->jobs.size(); ++i) {
    if (plan->jobs[i].kind == JobKind::kLocalize) last_of_map[plan->jobs[i].depends_on.front()] = i;
  }
  std::map<std::string, std::vector<Job>> groups;
  for (const Job& job : plan->jobs) {
    if (job.kind == JobKind::kLocalize) groups[job.depends_on.front()].push_back(job);
  }
  std::vector<Job> jobs;
  jobs.reserve(plan->jobs.size());
  for (size_t i = 0; i < plan->jobs.size(); ++i) {
    const Job& job = plan->jobs[i];
    if (job.kind != JobKind::kLocalize) {
      jobs.push_back(job);
      continue;
    }
    const std::string& map = job.depends_on.front();
    if (last_of_map.at(map) != i) continue;
    for (Job& grouped : groups.at(map)) jobs.push_back(std::move(grouped));
  }
  plan->jobs = std::move(jobs);
}

}  // namespace

ExperimentPlan PlanExperiment(const ExperimentOptions& options, const SessionClock& clock) {
  options.Check();
  ExperimentPlan plan;
  PlanBuilder builder(&plan);
  for (const std::string& label : options.features) {
    const FeatureSetup& feature = options.FeatureSetupOf(label);
    for (const MapSpec& map : options.maps) {
      for (const std::string& session : options.localization_sessions) {
        const MapSpec used =
            map.BuildsItsOwnMap() ? map : ParseMapSpec(ClosestSession(map, session, clock));
        const std::string job_id = builder.AddLocalize(feature, used, session);
        plan.cells.push_back({label, map.label, session, job_id});
      }
    }
    for (const ConsecutivePair& pair : options.consecutive_pairs) {
      const MapSpec map = ParseMapSpec(pair.map_session);
      const std::string job_id = builder.AddLocalize(feature, map, pair.localization_session);
      const int gap = ClockOf(clock, pair.localization_session, "consecutive pairs") -
                      ClockOf(clock, pair.map_session, "consecutive pairs");
      plan.consecutive.push_back({label, pair.map_session, pair.localization_session, gap,
                                  NearestClass(gap, options.consecutive_gap_classes_min),
                                  job_id});
    }
  }
  GroupLocalizationsByMap(&plan);
  return plan;
}

ExperimentPlan SelectShard(const ExperimentPlan& plan, int index, int count) {
  SLAM_THROW_IF_NOT(ConfigError, count >= 1 && index >= 0 && index < count)
      << "shard " << index << "/" << count << ": expected 0 <= index < count";
  std::set<std::string> keep;
  int map_number = 0;
  for (const Job& job : plan.jobs) {
    if (job.kind != JobKind::kBuildMap) continue;
    if (map_number++ % count != index) continue;
    keep.insert(job.id);
    keep.insert(job.depends_on.begin(), job.depends_on.end());
  }
  for (const Job& job : plan.jobs) {
    if (job.kind == JobKind::kLocalize && keep.count(job.depends_on.front()) > 0) {
      keep.insert(job.id);
      keep.insert(job.depends_on.begin(), job.depends_on.end());
    }
  }
  ExperimentPlan shard;
  for (const Job& job : plan.jobs) {
    if (keep.count(job.id) > 0) shard.jobs.push_back(job);
  }
  for (const MatrixCell& cell : plan.cells) {
    if (keep.count(cell.job_id) > 0) shard.cells.push_back(cell);
  }
  for (const ConsecutiveCell& cell : plan.consecutive) {
    if (keep.count(cell.job_id) > 0) shard.consecutive.push_back(cell);
  }
  return shard;
}

}  // namespace duskmap
