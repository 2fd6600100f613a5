#include "slam/synthetic/generator.h"

#include <set>

#include <atomic>
#include <exception>
#include <fstream>
#include <mutex>
#include <set>
#include <thread>

#include <nlohmann/json.hpp>

#include "slam/core/check.h"
#include "slam/core/random.h"
#include "slam/core/system_error.h"
#include "slam/core/timer.h"
#include "slam/io/folder_commit.h"
#include "slam/io/synthetic_dataset.h"
#include "slam/io/tum_writer.h"
#include "slam/synthetic/preview.h"
#include "slam/synthetic/scene/apartment.h"
#include "slam/synthetic/sensor/odometry.h"
#include "slam/synthetic/sensor/route.h"
#include "slam/synthetic/session_simulator.h"

namespace duskmap {
namespace {

void WriteSessionJson(const std::string& path, const SessionSpec& spec, const Scene& scene,
                      const SessionLighting& lighting, uint64_t seed, const GeneratedSessionSummary& summary) {
  nlohmann::json lamps = nlohmann::json::array();
  for (size_t i = 0; i < scene.lamps.size(); ++i) {
    lamps.push_back({{"name", scene.lamps[i].name}, {"room", scene.room_names[scene.lamps[i].room]},
                     {"on", static_cast<bool>(lighting.lamp_on[i])}, {"intensity_cd", scene.lamps[i].intensity_cd}});
  }
  nlohmann::json json = {
      {"name", spec.name},
      {"clock_time", spec.clock_time},
      {"role", spec.role},
      {"seed", seed},
      {"frames", summary.frames},
      {"distance_m", summary.distance_m},
      {"largest_step_m", summary.largest_step_m},
      {"sun_elevation_deg", lighting.sun.elevation_deg},
      {"sun_azimuth_deg", lighting.sun.azimuth_deg},
      {"sun_visible", lighting.sun_normal_lux_bgr[1] > 0.0f},
      {"sky_nits_green", lighting.sky_nits_bgr[1]},
      {"lamps", lamps},
      {"body_from_camera", "identity"}};
  // A session on a later day records its day and date; a day-0 session's
  // file stays as datasets of one day have always written it.
  if (spec.day != 0) {
    json["day"] = spec.day;
    json["day_of_year"] = lighting.day_of_year;
  }
  std::ofstream out(path);
  SLAM_THROW_IF_NOT(InputError, out.good()) << path << ": cannot write";
  out << json.dump(2) << "\n";
  SLAM_THROW_IF_NOT(InputError, out.good()) << path << ": write failed: " << LastSystemError();
}

GeneratedSessionSummary GenerateSession(const GeneratorConfig& config, const Scene& scene, size_t index,
                               const std::string& folder, SessionPreview* preview) {
  Stopwatch watch;
  const SessionSpec& spec = config.sessions[index];
  const uint64_t seed = GeneratorSessionSeed(config, index);
  const std::vector<TimedPose> route = GeneratorSessionRoute(config, index);
  std::vector<Rigid3d> world_from_camera;
  std::vector<double> times;
  for (const TimedPose& p : route) {
    world_from_camera.push_back(p.world_from_camera);
    times.push_back(p.time_s);
  }
  const std::vector<Rigid3d> odometry = SimulateOdometry(config.odometry, world_from_camera, times, DeriveSeed(seed, 11));
  const std::unique_ptr<SessionSimulator> started = StartSessionSimulator(config, scene, index, world_from_camera.front());
  SessionSimulator& simulator = *started;
  TumCalibration calibration;
  calibration.camera = config.camera.Intrinsics();
  calibration.depth_scale = 1000.0;
  TumSessionWriter writer(folder, calibration);
  GeneratedSessionSummary summary;
  summary.name = spec.name;
  summary.clock_time = spec.clock_time;
  const double start = SessionStartTimestamp(spec);
  for (size_t k = 0; k < route.size(); ++k) {
    RgbdFrame frame = simulator.Capture(world_from_camera[k]);
    frame.frame_index = static_cast<int64_t>(k);
    frame.timestamp_s = start + route[k].time_s;
    frame.odom_from_body = odometry[k];
    writer.Write(frame);
    summary.mean_brightness += simulator.camera().state().last_mean_brightness;
    summary.mean_gain += simulator.camera().state().gain;
    if (k > 0) summary.distance_m += (world_from_camera[k].translation - world_from_camera[k - 1].translation).norm();
  }
  writer.Finish();
  summary.frames = static_cast<int>(route.size());
  summary.largest_step_m = LargestStepM(route);
  summary.mean_brightness /= std::max(1, summary.frames);
  summary.mean_gain /= std::max(1, summary.frames);
  const Rigid3d world_from_odom = world_from_camera.front();
  summary.odometry_final_error_m =
      ((world_from_odom * odometry.back()).translation - world_from_camera.back().translation).norm();
  summary.sun_elevation_deg = simulator.lighting().sun.elevation_deg;
  summary.wall_s = watch.ElapsedMs() / 1000.0;
  WriteSessionJson(folder + "/session.json", spec, scene, simulator.lighting(), seed, summary);
  if (preview != nullptr) {
    std::vector<Eigen::Vector2d> route_xy;
    for (const Rigid3d& pose : world_from_camera) route_xy.push_back(pose.translation.head<2>());
    *preview = RenderSessionPreview(config, simulator, spec.name, spec.clock_time, route_xy, DeriveSeed(seed, 13));
  }
  return summary;
}

}  // namespace

ApartmentOptions GeneratorSceneOptions(const GeneratorConfig& config) {
  ApartmentOptions scene_options = config.scene;
  scene_options.seed = DeriveSeed(config.seed, 1);
  return scene_options;
}

Scene BuildGeneratorScene(const GeneratorConfig& config) { return BuildApartment(GeneratorSceneOptions(config)); }

uint64_t GeneratorSessionSeed(const GeneratorConfig& config, size_t index) { return DeriveSeed(config.seed, 100 + index); }

std::vector<TimedPose> GeneratorSessionRoute(const GeneratorConfig& config, size_t index) {
  std::vector<TimedPose> route =
      GenerateRoute(config.route, ApartmentPatrolRoute(), DeriveSeed(GeneratorSessionSeed(config, index), 10));
  if (config.max_frames > 0 && static_cast<int>(route.size()) > config.max_frames) route.resize(config.max_frames);
  return route;
}

std::unique_ptr<SessionSimulator> StartSessionSimulator(const GeneratorConfig& config, const Scene& scene,
                                                        size_t index, const Rigid3d& first_world_from_camera) {
  const SessionSpec& spec = config.sessions[index];
  auto simulator = std::make_unique<SessionSimulator>(config, scene,
                                                      ParseClockTime(spec.clock_time, "sessions." + spec.name),
                                                      DeriveSeed(GeneratorSessionSeed(config, index), 12), spec.day);
  simulator->Settle(first_world_from_camera, 12);
  return simulator;
}

double SessionStartTimestamp(const SessionSpec& session) {
  return session.day * 86400.0 + ParseClockTime(session.clock_time, "sessions." + session.name) * 3600.0;
}

GenerateSummary GenerateDataset(const GeneratorConfig& config, const GenerateOptions& options) {
  config.Check();
  Stopwatch watch;
  StagedFolder staged(options.output_path, options.overwrite, OwnedDataset());
  const Scene scene = BuildGeneratorScene(config);

  GenerateSummary summary;
  summary.sessions.resize(config.sessions.size());
  std::vector<SessionPreview> previews(options.preview ? config.sessions.size() : 0);
  std::atomic<size_t> next{0};
  std::mutex error_mutex;
  std::exception_ptr error;
  auto worker = [&] {
    for (size_t i = next++; i < config.sessions.size(); i = next++) {
      try {
        summary.sessions[i] = GenerateSession(config, scene, i, staged.staging_path() + "/" + config.sessions[i].name,
                                              options.preview ? &previews[i] : nullptr);
      } catch (...) {
        std::lock_guard<std::mutex> lock(error_mutex);
        if (!error) error = std::current_exception();
      }
    }
  };
  const int threads = std::min<int>(config.threads, static_cast<int>(config.sessions.size()));
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
  if (error) std::rethrow_exception(error);

  DatasetManifest manifest;
  for (size_t i = 0; i < config.sessions.size(); ++i) {
    const SessionSpec& s = config.sessions[i];
    manifest.sessions.push_back({s.name, s.name, s.clock_time, s.role, summary.sessions[i].largest_step_m});
  }
  std::set<std::string> credited;
  for (const SceneMesh& mesh : scene.meshes) {
    const std::string source = mesh.catalog + "#" + mesh.model_id;
    if (!credited.insert(source).second) continue;
    manifest.assets.push_back({mesh.name, source, mesh.creator, mesh.license});
  }
  for (const AssetCredit& credit : scene.material_credits) {
    manifest.assets.push_back({credit.name, credit.source, credit.creator, credit.license});
  }
  WriteManifest(staged.staging_path(), manifest);
  if (options.preview) WritePreviews(scene, previews, staged.staging_path() + "/previews");
  staged.Commit();
  summary.output_path = staged.final_path();
  summary.wall_s = watch.ElapsedMs() / 1000.0;
  return summary;
}

}  // namespace duskmap
