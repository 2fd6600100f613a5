// Pose-graph optimisation of synthetic multi-session graphs (the setting of
// the paper's merged maps): S sessions, each one lap of a 6 m circle with
// drifting odometry, each started in its own odometry frame; one loop closure
// per session from its last to its first node and, every 5th node, an
// inter-session loop closure to the same place in the previous session. The
// whole graph is optimised at once (all sessions joined in session 0's frame,
// poses re-initialised from the links as after a new connection), with the
// max-error check. Report medians:
//   build-reg/bench/graph_bench --benchmark_repetitions=5
//       --benchmark_report_aggregates_only=true
#include <cmath>

#include <benchmark/benchmark.h>

#include "slam/core/random.h"
#include "slam/graph/pose_graph_optimizer.h"

namespace duskmap {
namespace {

Information6d Diagonal(double sigma_m, double sigma_rad) {
  Information6d information = Information6d::Zero();
  information.diagonal() << Eigen::Vector3d::Constant(1.0 / (sigma_m * sigma_m)),
      Eigen::Vector3d::Constant(1.0 / (sigma_rad * sigma_rad));
  return information;
}

Rigid3d TruePose(int k, int per_session, int session) {
  const double angle = 2.0 * M_PI * k / per_session;
  const double radius = 3.0 + 0.05 * session;
  return Rigid3d(Eigen::Quaterniond(Eigen::AngleAxisd(angle + M_PI / 2, Eigen::Vector3d::UnitZ())),
                 Eigen::Vector3d(radius * std::cos(angle), radius * std::sin(angle), 0.0));
}

Rigid3d Noisy(const Rigid3d& motion, double yaw_bias, Rng* rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  const Eigen::Quaterniond dq =
      Eigen::AngleAxisd(0.002 * n(*rng), Eigen::Vector3d::UnitX()) *
      Eigen::AngleAxisd(0.002 * n(*rng), Eigen::Vector3d::UnitY()) *
      Eigen::AngleAxisd(yaw_bias + 0.002 * n(*rng), Eigen::Vector3d::UnitZ());
  return Rigid3d(motion.rotation * dq,
                 motion.translation + 0.005 * Eigen::Vector3d(n(*rng), n(*rng), n(*rng)));
}

Link MakeLink(NodeId from, NodeId to, LinkType type, const Rigid3d& t, const Information6d& info) {
  Link link;
  link.from = from;
  link.to = to;
  link.type = type;
  link.from_from_to = t;
  link.information = info;
  return link;
}

PoseGraph MultiSessionGraph(int num_nodes, int num_sessions) {
  Rng rng(42);
  PoseGraph graph;
  std::uniform_real_distribution<double> offset(-5.0, 5.0), yaw(-M_PI, M_PI);
  NodeId first = 1;
  NodeId previous_first = 0;
  int previous_count = 0;
  for (int s = 0; s < num_sessions; ++s) {
    const int count = num_nodes / num_sessions + (s < num_nodes % num_sessions ? 1 : 0);
    const Rigid3d odom_from_world =
        s == 0 ? Rigid3d()
               : Rigid3d(Eigen::Quaterniond(Eigen::AngleAxisd(yaw(rng), Eigen::Vector3d::UnitZ())),
                         Eigen::Vector3d(offset(rng), offset(rng), 0.0));
    Rigid3d pose = odom_from_world * TruePose(0, count, s);
    graph.AddNode(first, s, pose);
    for (int k = 1; k < count; ++k) {
      const Rigid3d motion =
          Noisy(TruePose(k - 1, count, s).Inverse() * TruePose(k, count, s), 0.003, &rng);
      pose = pose * motion;
      graph.AddNode(first + k, s, pose);
      graph.AddLink(MakeLink(first + k - 1, first + k, LinkType::kOdometry, motion,
                             Diagonal(0.05, 0.01)));
    }
    graph.AddLink(MakeLink(first + count - 1, first, LinkType::kLoopClosure,
                           TruePose(count - 1, count, s).Inverse() * TruePose(0, count, s),
                           Diagonal(0.02, 0.01)));
    for (int k = 0; s > 0 && k < count; k += 5) {
      // The same place (same angle on the circle) in the previous session.
      const int j = static_cast<int>(std::lround(double(k) * previous_count / count)) %
                    previous_count;
      graph.AddLink(MakeLink(first + k, previous_first + j, LinkType::kLoopClosure,
                             TruePose(k, count, s).Inverse() *
                                 TruePose(j, previous_count, s - 1),
                             Diagonal(0.02, 0.01)));
    }
    previous_first = first;
    previous_count = count;
    first += count;
  }
  return graph;
}

void BM_OptimizePoseGraph(benchmark::State& state) {
  const int num_nodes = static_cast<int>(state.range(0));
  const PoseGraph original = MultiSessionGraph(num_nodes, 6);
  PoseGraphOptimizerOptions options;
  options.initialization = PoseInitialization::kEveryOptimization;  // as after a new connection
  OptimizationSummary summary;
  for (auto _ : state) {
    state.PauseTiming();
    PoseGraph graph = original;
    state.ResumeTiming();
    summary = OptimizePoseGraph(options, {}, &graph);
    benchmark::DoNotOptimize(summary.final_cost);
  }
  state.counters["nodes"] = summary.num_nodes;
  state.counters["links"] = summary.num_links;
  state.counters["iterations"] = summary.num_iterations;
  state.counters["accepted"] = summary.accepted();
  state.counters["solve_ms"] = summary.solve_ms;
  state.counters["max_lin_ratio"] = summary.max_errors.linear.ratio;
}

BENCHMARK(BM_OptimizePoseGraph)->Arg(200)->Arg(1200)->Arg(10000)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace duskmap

BENCHMARK_MAIN();
