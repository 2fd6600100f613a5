#include "slam/synthetic/sensor/route.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <utility>

#include "slam/core/check.h"
#include "slam/core/random.h"

namespace duskmap {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;

// Piecewise-linear nominal motion: (nominal time, x, y, yaw, nominal distance walked).
struct Key {
  double t, x, y, yaw, s;
};

double WrapAngle(double a) {
  while (a > kPi) a -= 2 * kPi;
  while (a < -kPi) a += 2 * kPi;
  return a;
}

std::vector<Key> NominalKeys(const RouteOptions& o, const std::vector<RouteWaypoint>& waypoints,
                             double speed_factor) {
  SLAM_CHECK(!waypoints.empty());
  std::vector<Key> keys;
  double t = 0.0;
  Eigen::Vector2d p = waypoints[0].position_xy;
  double yaw = std::isnan(waypoints[0].face_yaw_deg) ? 0.0 : waypoints[0].face_yaw_deg * kDeg;
  keys.push_back({t, p.x(), p.y(), yaw, 0.0});
  double s = 0.0;
  auto turn_to = [&](double target_yaw, double speed_dps) {
    const double delta = WrapAngle(target_yaw - yaw);
    if (std::abs(delta) < 1e-9) return;
    t += std::abs(delta) / (speed_dps * kDeg * speed_factor);
    yaw += delta;
    keys.push_back({t, p.x(), p.y(), yaw, s});
  };
  auto after_arrival = [&](const RouteWaypoint& w) {
    if (w.spin_deg != 0.0) {
      t += std::abs(w.spin_deg) / (o.turn_speed_dps * speed_factor);
      yaw += w.spin_deg * kDeg;
      keys.push_back({t, p.x(), p.y(), yaw, s});
    }
    if (!std::isnan(w.face_yaw_deg)) turn_to(w.face_yaw_deg * kDeg, o.corner_turn_speed_dps);
    if (w.hold_s > 0.0) {
      t += w.hold_s;
      keys.push_back({t, p.x(), p.y(), yaw, s});
    }
  };
  after_arrival(waypoints[0]);
  for (size_t i = 1; i < waypoints.size(); ++i) {
    const Eigen::Vector2d next = waypoints[i].position_xy;
    const Eigen::Vector2d step = next - p;
    if (step.norm() > 1e-6) {
      turn_to(std::atan2(step.y(), step.x()), o.corner_turn_speed_dps);
      t += step.norm() / (o.speed_mps * speed_factor);
      s += step.norm();
      p = next;
      keys.push_back({t, p.x(), p.y(), yaw, s});
    }
    after_arrival(waypoints[i]);
  }
  return keys;
}

Key Interpolate(const std::vector<Key>& keys, double t) {
  if (t <= keys.front().t) return keys.front();
  for (size_t i = 1; i < keys.size(); ++i) {
    if (t <= keys[i].t) {
      const Key& a = keys[i - 1];
      const Key& b = keys[i];
      const double s = (b.t - a.t) > 1e-12 ? (t - a.t) / (b.t - a.t) : 1.0;
      return {t, a.x + s * (b.x - a.x), a.y + s * (b.y - a.y), a.yaw + s * (b.yaw - a.yaw), a.s + s * (b.s - a.s)};
    }
  }
  return keys.back();
}

// A smooth random signal in [-1, 1]: two sinusoids of random period/phase.
struct Wobble {
  double w1 = 0, p1 = 0, w2 = 0, p2 = 0;
  Wobble() = default;
  Wobble(Rng& rng, double min_period_s, double max_period_s) {
    std::uniform_real_distribution<double> period(min_period_s, max_period_s), phase(0.0, 2 * kPi);
    w1 = 2 * kPi / period(rng);
    p1 = phase(rng);
    w2 = 2 * kPi / period(rng);
    p2 = phase(rng);
  }
  double operator()(double t) const { return 0.6 * std::sin(w1 * t + p1) + 0.4 * std::sin(w2 * t + p2); }
};

// The session's walk: the nominal path with the walker's wander, which is a
// function of the distance walked (a person drifts across the corridor as
// they walk, not while turning in place).
class Walk {
 public:
  Walk(const RouteOptions& o, std::vector<Key> keys, Rng& rng)
      : keys_(std::move(keys)),
        lateral_m_(o.lateral_max_m / std::sqrt(2.0)),  // |(off_x, off_y)| <= lateral_max
        off_x_(rng, kWanderMinWavelengthM, kWanderMaxWavelengthM),
        off_y_(rng, kWanderMinWavelengthM, kWanderMaxWavelengthM) {}

  const std::vector<Key>& keys() const { return keys_; }
  double nominal_duration_s() const { return keys_.back().t; }

  // The walker's position and nominal yaw at nominal time tau.
  Key At(double tau) const {
    Key key = Interpolate(keys_, tau);
    // Deviations fade in and out over the first and last metres so sessions
    // start and end at the docking view.
    const double length = keys_.back().s;
    const double taper = std::max(0.0, std::min({1.0, key.s / kTaperM, (length - key.s) / kTaperM}));
    key.x += taper * lateral_m_ * off_x_(key.s);
    key.y += taper * lateral_m_ * off_y_(key.s);
    return key;
  }

 private:
  static constexpr double kWanderMinWavelengthM = 3.5;
  static constexpr double kWanderMaxWavelengthM = 11.0;
  static constexpr double kTaperM = 2.0;
  std::vector<Key> keys_;
  double lateral_m_;
  Wobble off_x_, off_y_;
};

// Nominal time -> walked time. The walker keeps its session speed along the
// path it actually walks, wander included, so the wander changes how long
// the walk takes, not how fast it goes, and no step between frames is longer
// than the session speed times the frame period. Returns samples (tau, t), increasing.
std::vector<std::pair<double, double>> WalkedTime(const Walk& walk) {
  constexpr double kStepS = 0.01;
  const double end = walk.nominal_duration_s();
  std::vector<std::pair<double, double>> samples{{0.0, 0.0}};
  Key previous = walk.At(0.0);
  Key previous_nominal = Interpolate(walk.keys(), 0.0);
  double t = 0.0;
  for (double tau = kStepS; previous.t < end; tau = std::min(end, tau + kStepS)) {
    const Key now = walk.At(tau);
    const Key nominal = Interpolate(walk.keys(), tau);
    const double nominal_m = std::hypot(nominal.x - previous_nominal.x, nominal.y - previous_nominal.y);
    const double walked_m = std::hypot(now.x - previous.x, now.y - previous.y);
    // Walking: as long as the walked distance at the nominal speed; turning or
    // holding in place: the nominal time.
    t += nominal_m > 1e-12 ? (now.t - previous.t) * walked_m / nominal_m : now.t - previous.t;
    samples.emplace_back(tau, t);
    previous = now;
    previous_nominal = nominal;
  }
  return samples;
}

// Inverse of WalkedTime: the nominal time at walked time t.
double NominalTimeAt(const std::vector<std::pair<double, double>>& samples, double t) {
  const auto after = std::lower_bound(samples.begin(), samples.end(), t,
                                      [](const std::pair<double, double>& s, double v) { return s.second < v; });
  if (after == samples.begin()) return samples.front().first;
  if (after == samples.end()) return samples.back().first;
  const auto before = after - 1;
  const double span = after->second - before->second;
  const double f = span > 1e-12 ? (t - before->second) / span : 1.0;
  return before->first + f * (after->first - before->first);
}

}  // namespace

double RouteOptions::LargestStepBoundM() const {
  const double walked_m = speed_mps * (1.0 + speed_variation) / frame_rate_hz;
  return std::hypot(walked_m, 2.0 * bob_m);  // the bob moves the camera by at most 2 bob_m
}

void RouteOptions::Check() const {
  SLAM_THROW_IF_NOT(ConfigError, speed_mps > 0.05 && speed_mps < 3.0) << "route.speed_mps must be in (0.05, 3), got " << speed_mps;
  SLAM_THROW_IF_NOT(ConfigError, turn_speed_dps > 0 && corner_turn_speed_dps > 0) << "route turn speeds must be > 0";
  SLAM_THROW_IF_NOT(ConfigError, frame_rate_hz > 0 && frame_rate_hz <= 60) << "route.frame_rate_hz must be in (0, 60], got " << frame_rate_hz;
  SLAM_THROW_IF_NOT(ConfigError, height_m > 0.3 && height_m < 2.4) << "route.height_m must be in (0.3, 2.4), got " << height_m;
  SLAM_THROW_IF_NOT(ConfigError, height_spread_m >= 0 && height_spread_m < 0.3) << "route.height_spread_m must be in [0, 0.3)";
  SLAM_THROW_IF_NOT(ConfigError, lateral_max_m >= 0 && lateral_max_m <= 0.3) << "route.lateral_max_m must be in [0, 0.3] (doorways), got " << lateral_max_m;
  SLAM_THROW_IF_NOT(ConfigError, heading_max_deg >= 0 && heading_max_deg <= 30) << "route.heading_max_deg must be in [0, 30]";
  SLAM_THROW_IF_NOT(ConfigError, speed_variation >= 0 && speed_variation < 0.5) << "route.speed_variation must be in [0, 0.5)";
  SLAM_THROW_IF_NOT(ConfigError, sway_deg >= 0 && sway_deg < 10) << "route.sway_deg must be in [0, 10)";
  SLAM_THROW_IF_NOT(ConfigError, bob_m >= 0 && bob_m < 0.1) << "route.bob_m must be in [0, 0.1)";
  SLAM_THROW_IF_NOT(ConfigError, std::abs(pitch_deg) < 45) << "route.pitch_deg must be in (-45, 45)";
  SLAM_THROW_IF_NOT(ConfigError, max_step_m > 0 && max_step_m <= 1000) << "route.max_step_m must be in (0, 1000], got " << max_step_m;
  SLAM_THROW_IF_NOT(ConfigError, !paced_walk || LargestStepBoundM() <= max_step_m)
      << "route.speed_mps " << speed_mps << " (up to x" << 1.0 + speed_variation << " with route.speed_variation, at route.frame_rate_hz "
      << frame_rate_hz << ", route.bob_m " << bob_m << ") moves the camera up to " << LargestStepBoundM()
      << " m between frames, more than route.max_step_m " << max_step_m;
}

namespace {

// The walk of the models up to run 23: the wander, a function of time, is
// added to the nominal walk at the session speed.
std::vector<TimedPose> TimedWanderRoute(const RouteOptions& o, const std::vector<RouteWaypoint>& waypoints,
                                        uint64_t seed) {
  Rng rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const double speed_factor = 1.0 + o.speed_variation * unit(rng);
  const double height = o.height_m + o.height_spread_m * unit(rng);
  const Wobble off_x(rng, 6.0, 20.0), off_y(rng, 6.0, 20.0), heading(rng, 4.0, 15.0);
  const Wobble pitch(rng, 2.0, 5.0), roll(rng, 2.0, 6.0), bob(rng, 0.8, 1.6);
  const std::vector<Key> keys = NominalKeys(o, waypoints, speed_factor);
  const double duration = keys.back().t;
  const double dt = 1.0 / o.frame_rate_hz;
  const int frames = static_cast<int>(std::floor(duration / dt)) + 1;
  const double lateral = o.lateral_max_m / std::sqrt(2.0);
  std::vector<TimedPose> poses;
  for (int k = 0; k < frames; ++k) {
    const double t = (k == frames - 1) ? duration : k * dt;
    const Key key = Interpolate(keys, t);
    const double taper = std::min({1.0, t / 4.0, (duration - t) / 4.0});
    const double x = key.x + taper * lateral * off_x(t);
    const double y = key.y + taper * lateral * off_y(t);
    const double yaw = key.yaw + taper * o.heading_max_deg * kDeg * heading(t);
    const double pitch_rad = (o.pitch_deg + o.sway_deg * pitch(t)) * kDeg;
    const double roll_rad = o.sway_deg * roll(t) * kDeg;
    const double z = height + o.bob_m * bob(t);
    poses.push_back({t, Rigid3d(CameraRotationFromYawPitchRoll(yaw, pitch_rad, roll_rad), Eigen::Vector3d(x, y, z))});
  }
  return poses;
}

// The paced walk (run 24 on).
std::vector<TimedPose> PacedRoute(const RouteOptions& o, const std::vector<RouteWaypoint>& waypoints, uint64_t seed) {
  Rng rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const double speed_factor = 1.0 + o.speed_variation * unit(rng);
  const double height = o.height_m + o.height_spread_m * unit(rng);
  const Walk walk(o, NominalKeys(o, waypoints, speed_factor), rng);
  const Wobble heading(rng, 4.0, 15.0), pitch(rng, 2.0, 5.0), roll(rng, 2.0, 6.0), bob(rng, 0.8, 1.6);
  const std::vector<std::pair<double, double>> walked = WalkedTime(walk);
  const double duration = walked.back().second;
  const double dt = 1.0 / o.frame_rate_hz;
  const int frames = static_cast<int>(std::floor(duration / dt)) + 1;
  std::vector<TimedPose> poses;
  for (int k = 0; k < frames; ++k) {
    // The last frame is exactly at the end, facing the docking picture.
    const double t = (k == frames - 1) ? duration : k * dt;
    const Key key = walk.At(NominalTimeAt(walked, t));
    // The heading's deviation fades in and out over 4 s.
    const double taper = std::max(0.0, std::min({1.0, t / 4.0, (duration - t) / 4.0}));
    const double yaw = key.yaw + taper * o.heading_max_deg * kDeg * heading(t);
    const double pitch_rad = (o.pitch_deg + o.sway_deg * pitch(t)) * kDeg;
    const double roll_rad = o.sway_deg * roll(t) * kDeg;
    const double z = height + o.bob_m * bob(t);
    poses.push_back({t, Rigid3d(CameraRotationFromYawPitchRoll(yaw, pitch_rad, roll_rad), Eigen::Vector3d(key.x, key.y, z))});
  }
  return poses;
}

}  // namespace

std::vector<TimedPose> GenerateRoute(const RouteOptions& o, const std::vector<RouteWaypoint>& waypoints,
                                     uint64_t seed) {
  o.Check();
  std::vector<TimedPose> poses = o.paced_walk ? PacedRoute(o, waypoints, seed) : TimedWanderRoute(o, waypoints, seed);
  for (size_t k = 1; k < poses.size(); ++k) {
    const double step_m = (poses[k].world_from_camera.translation - poses[k - 1].world_from_camera.translation).norm();
    SLAM_THROW_IF_NOT(ConfigError, step_m <= o.max_step_m + 1e-4)
        << "route.max_step_m " << o.max_step_m << ": the walk moves the camera " << step_m << " m between frames "
        << k - 1 << " and " << k << " (seed " << seed << "; route.speed_mps " << o.speed_mps << ", route.paced_walk "
        << (o.paced_walk ? "true" : "false") << ")";
  }
  return poses;
}

double LargestStepM(const std::vector<TimedPose>& route) {
  double largest_m = 0.0;
  for (size_t k = 1; k < route.size(); ++k) {
    largest_m = std::max(largest_m, (route[k].world_from_camera.translation - route[k - 1].world_from_camera.translation).norm());
  }
  return largest_m;
}

}  // namespace duskmap
