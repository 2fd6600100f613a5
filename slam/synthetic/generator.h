// `duskmap generate`: builds the apartment, then for every session walks the
// route, renders and captures each frame, simulates odometry and writes the
// session in the TUM layout; the whole dataset is written into a temporary
// sibling folder and renamed into place only when complete. Sessions run on
// config.threads threads, one session per thread; the output is identical
// for any thread count.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "slam/synthetic/generator_config.h"
#include "slam/synthetic/scene/scene.h"
#include "slam/synthetic/sensor/route.h"
#include "slam/synthetic/session_simulator.h"

namespace duskmap {

struct GenerateOptions {
  std::string output_path;  // dataset folder to create
  bool overwrite = false;   // replace an existing folder
  bool preview = false;     // also write previews/ (see preview.h)
};

struct GeneratedSessionSummary {
  std::string name;
  std::string clock_time;
  int frames = 0;
  double distance_m = 0.0;          // ground-truth path length
  double largest_step_m = 0.0;      // largest camera move between consecutive frames
  double sun_elevation_deg = 0.0;
  double mean_brightness = 0.0;     // mean output brightness over frames, [0, 1]
  double mean_gain = 0.0;           // mean analogue gain over frames
  double odometry_final_error_m = 0.0;  // odometry vs ground truth at the last frame
  double wall_s = 0.0;
};

struct GenerateSummary {
  std::vector<GeneratedSessionSummary> sessions;
  double wall_s = 0.0;
  std::string output_path;
};

GenerateSummary GenerateDataset(const GeneratorConfig& config, const GenerateOptions& options);

// The apartment a config renders: config.scene with its texture seed derived
// from config.seed (the seed that ApartmentOptions::seed holds when built).
ApartmentOptions GeneratorSceneOptions(const GeneratorConfig& config);
Scene BuildGeneratorScene(const GeneratorConfig& config);

// Session `index` of config.sessions: its seed, its route's ground-truth
// poses (the first config.max_frames when set), and its simulator at the
// session's clock time with the camera settled on `first_world_from_camera`,
// as the generator records it.
uint64_t GeneratorSessionSeed(const GeneratorConfig& config, size_t index);
std::vector<TimedPose> GeneratorSessionRoute(const GeneratorConfig& config, size_t index);
std::unique_ptr<SessionSimulator> StartSessionSimulator(const GeneratorConfig& config, const Scene& scene,
                                                        size_t index, const Rigid3d& first_world_from_camera);

// Seconds at which a session's first frame is recorded: its day x 86400 plus
// the seconds of its local clock time (day 0: the seconds of the local day).
double SessionStartTimestamp(const SessionSpec& session);

}  // namespace duskmap
