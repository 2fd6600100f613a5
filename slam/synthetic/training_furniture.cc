#include "slam/synthetic/training_furniture.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>
#include <random>

#include "slam/core/check.h"
#include "slam/core/random.h"
#include "slam/synthetic/generator_models.h"

namespace duskmap {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kLargerBy = 0.15;       // a model's footprint may exceed its place's by this, metres
constexpr double kWallNear = 0.12;       // a default piece this close to a wall stays against it
constexpr double kMaxClearance = 0.30;   // route clearance asked of a place that had more
constexpr double kDropSmall = 0.2;       // share of floor and surface objects left out
constexpr int kTries = 12;               // draws of a place before it keeps its default piece
constexpr double kMaxTopM = 1.6;         // highest top of a piece something stands on
constexpr double kCeilingM = 2.4;        // highest top of any piece (the ceiling is at 2.5 m)

Eigen::Vector2d Rotated(const Eigen::Vector2d& v, double yaw_deg) {
  const double a = yaw_deg * kPi / 180.0;
  return {std::cos(a) * v.x() - std::sin(a) * v.y(), std::sin(a) * v.x() + std::cos(a) * v.y()};
}

bool IsLarge(const std::string& group) { return group == "seat" || group == "storage" || group == "bed"; }

// How far a piece of `group` may turn and move from its place.
struct Jitter {
  double yaw_deg = 0.0;
  double move_m = 0.0;
};

Jitter JitterOf(const std::string& group, bool supported) {
  if (supported) return {30.0, 0.05};
  if (IsLarge(group)) return {4.0, 0.15};
  if (group == "table") return {10.0, 0.15};
  if (group == "wall") return {0.0, 0.15};
  if (group == "surface") return {30.0, 0.10};
  return {30.0, 0.15};  // chairs and floor objects
}

// One place of the default arrangement.
struct Place {
  FurniturePiece piece;  // the default piece
  std::string group;
  Eigen::Vector3d size_m;
  RoomFloor floor;
  std::array<bool, 4> against_wall{};  // min x, max x, min y, max y of its box
  std::optional<size_t> support;       // the place it stands on
  bool carries = false;                // something stands on it
  double clearance_m = 0.0;            // asked of any piece put here
  double overlap = 0.0;                // FloorOverlap allowed here
};

const RoomFloor& FloorOf(const std::vector<RoomFloor>& floors, const std::string& room) {
  for (const RoomFloor& f : floors) {
    if (f.name == room) return f;
  }
  SLAM_CHECK_MSG(false, ("no room '" + room + "'").c_str());
  return floors.front();
}

// The group of a default piece: of a piece above the floor, its surface or
// wall group; otherwise its floor-standing one.
std::string GroupOf(const FurniturePiece& piece) {
  const bool raised = piece.elevation_m > 0.05;
  for (const TrainingFurnitureModel& m : TrainingFurnitureModels()) {
    const bool raised_group = m.group == "surface" || m.group == "wall";
    if (m.model == piece.model && raised_group == raised) return m.group;
  }
  SLAM_CHECK_MSG(false, ("default piece '" + piece.model + "' has no training group").c_str());
  return "";
}

std::optional<size_t> SupportOf(const std::vector<Place>& places, const FurniturePiece& piece) {
  if (piece.elevation_m <= 0.05) return std::nullopt;
  for (size_t j = 0; j < places.size(); ++j) {
    const Place& p = places[j];
    if (p.piece.elevation_m > 0.0 || std::abs(p.size_m.z() - piece.elevation_m) > 0.06) continue;
    const Eigen::Vector2d half = FootprintHalfExtentsM(p.piece, p.size_m);
    if (((piece.position_m - p.piece.position_m).cwiseAbs().array() <= half.array()).all()) return j;
  }
  return std::nullopt;
}

bool InFootprint(const Eigen::Vector2d& point, const FurniturePiece& piece, const Eigen::Vector3d& size_m) {
  const Eigen::Vector2d local = Rotated(point - piece.position_m, -piece.yaw_deg);
  return std::abs(local.x()) <= 0.5 * size_m.x() && std::abs(local.y()) <= 0.5 * size_m.y();
}

// The share of a's footprint (a 16 x 16 grid of points) inside b's.
double ShareInside(const FurniturePiece& a, const FurniturePiece& b) {
  const Eigen::Vector3d size_a = TrainingFurnitureSize(a.model), size_b = TrainingFurnitureSize(b.model);
  const double reach = 0.5 * (size_a.head<2>().norm() + size_b.head<2>().norm());
  if ((a.position_m - b.position_m).norm() > reach) return 0.0;
  int inside = 0;
  for (int i = 0; i < 16; ++i) {
    for (int j = 0; j < 16; ++j) {
      const Eigen::Vector2d local(((i + 0.5) / 16 - 0.5) * size_a.x(), ((j + 0.5) / 16 - 0.5) * size_a.y());
      inside += InFootprint(a.position_m + Rotated(local, a.yaw_deg), b, size_b);
    }
  }
  return inside / 256.0;
}

// How much a floor piece and the other floor pieces cover of each other:
// the largest share of either footprint inside the other's.
double FloorOverlap(const FurniturePiece& piece, const std::vector<FurniturePiece>& others) {
  double largest = 0.0;
  if (piece.elevation_m != 0.0) return largest;
  for (const FurniturePiece& other : others) {
    if (other.elevation_m != 0.0) continue;
    largest = std::max({largest, ShareInside(piece, other), ShareInside(other, piece)});
  }
  return largest;
}

// The pieces around place `index` while it is drawn: the ones drawn before
// it and the default pieces of the places after it.
std::vector<FurniturePiece> Neighbours(const std::vector<Place>& places, const std::vector<FurniturePiece>& drawn,
                                       size_t index) {
  std::vector<FurniturePiece> out(drawn.begin(), drawn.begin() + static_cast<std::ptrdiff_t>(index));
  for (size_t k = index + 1; k < places.size(); ++k) out.push_back(places[k].piece);
  return out;
}

std::vector<Place> DefaultPlaces() {
  const std::vector<RoomFloor> floors = ApartmentRoomFloors();
  const std::vector<RouteWaypoint> route = ApartmentPatrolRoute();
  std::vector<Place> places;
  for (const FurniturePiece& piece : DefaultFurniturePieces()) {
    Place p;
    p.piece = piece;
    p.group = GroupOf(piece);
    p.size_m = TrainingFurnitureSize(piece.model);
    p.floor = FloorOf(floors, piece.room);
    const Eigen::Vector2d half = FootprintHalfExtentsM(piece, p.size_m);
    const Eigen::Vector2d lo = piece.position_m - half, hi = piece.position_m + half;
    p.against_wall = {lo.x() - p.floor.min_xy.x() < kWallNear, p.floor.max_xy.x() - hi.x() < kWallNear,
                      lo.y() - p.floor.min_xy.y() < kWallNear, p.floor.max_xy.y() - hi.y() < kWallNear};
    p.support = SupportOf(places, piece);
    p.clearance_m = std::min(RouteClearanceM(piece, p.size_m, route), kMaxClearance) - 0.005;
    if (p.support) places[*p.support].carries = true;
    places.push_back(p);
  }
  for (size_t i = 0; i < places.size(); ++i) {
    std::vector<FurniturePiece> others;
    for (size_t k = 0; k < places.size(); ++k) {
      if (k != i) others.push_back(places[k].piece);
    }
    places[i].overlap = FloorOverlap(places[i].piece, others) + 0.05;
  }
  return places;
}

// The models of the place's group that fit its footprint.
std::vector<const TrainingFurnitureModel*> Candidates(const Place& place) {
  std::vector<const TrainingFurnitureModel*> out;
  for (const TrainingFurnitureModel& m : TrainingFurnitureModels()) {
    if (m.group == place.group && m.size_m.x() <= place.size_m.x() + kLargerBy &&
        m.size_m.y() <= place.size_m.y() + kLargerBy && (!place.carries || m.size_m.z() <= kMaxTopM)) {
      out.push_back(&m);
    }
  }
  return out;
}

// Keeps the sides of the box that were against a wall where they were and
// the box inside its room; false when it cannot be.
bool FitToRoom(const Place& place, const Eigen::Vector3d& size_m, FurniturePiece* piece) {
  const Eigen::Vector2d half0 = FootprintHalfExtentsM(place.piece, place.size_m);
  const Eigen::Vector2d half = FootprintHalfExtentsM(*piece, size_m);
  for (int axis = 0; axis < 2; ++axis) {
    double& c = piece->position_m[axis];
    if (place.against_wall[2 * axis]) {
      c = place.piece.position_m[axis] - half0[axis] + half[axis];
    } else if (place.against_wall[2 * axis + 1]) {
      c = place.piece.position_m[axis] + half0[axis] - half[axis];
    }
    const double lo = place.floor.min_xy[axis] + half[axis] + 0.005;
    const double hi = place.floor.max_xy[axis] - half[axis] - 0.005;
    if (lo > hi) return false;
    c = std::clamp(c, lo, hi);
  }
  return true;
}

// A piece on `support` (its default and its drawn piece): its place on the
// support's top carried along, scaled to a smaller top, at the top's height.
FurniturePiece OnSupport(const Place& place, const Place& support, const FurniturePiece& drawn_support,
                         const Eigen::Vector2d& own_move, double own_yaw_deg) {
  const Eigen::Vector3d top = TrainingFurnitureSize(drawn_support.model);
  Eigen::Vector2d local = Rotated(place.piece.position_m - support.piece.position_m, -support.piece.yaw_deg);
  local.x() *= std::min(1.0, top.x() / support.size_m.x());
  local.y() *= std::min(1.0, top.y() / support.size_m.y());
  local += own_move;
  local.x() = std::clamp(local.x(), -std::max(0.0, top.x() / 2 - 0.08), std::max(0.0, top.x() / 2 - 0.08));
  local.y() = std::clamp(local.y(), -std::max(0.0, top.y() / 2 - 0.08), std::max(0.0, top.y() / 2 - 0.08));
  FurniturePiece piece = place.piece;
  piece.position_m = drawn_support.position_m + Rotated(local, drawn_support.yaw_deg);
  piece.yaw_deg = place.piece.yaw_deg + (drawn_support.yaw_deg - support.piece.yaw_deg) + own_yaw_deg;
  piece.elevation_m = top.z();
  return piece;
}

// Inside its room, below the ceiling, off the route, and overlapping the
// floor pieces around it no more than the default piece did.
bool Acceptable(const std::vector<Place>& places, const FurniturePiece& piece, const std::vector<FurniturePiece>& drawn,
                size_t index, const std::vector<RouteWaypoint>& route) {
  const Place& place = places[index];
  const Eigen::Vector3d size = TrainingFurnitureSize(piece.model);
  if (FloorOverlap(piece, Neighbours(places, drawn, index)) > place.overlap) return false;
  const Eigen::Vector2d half = FootprintHalfExtentsM(piece, size);
  const bool inside = ((piece.position_m - half - place.floor.min_xy).array() >= -1e-9).all() &&
                      ((place.floor.max_xy - piece.position_m - half).array() >= -1e-9).all();
  return inside && piece.elevation_m + size.z() <= kCeilingM && RouteClearanceM(piece, size, route) >= place.clearance_m;
}

// One draw for a place: a model of its group, turned and moved.
std::optional<FurniturePiece> DrawOnce(const std::vector<Place>& places, const std::vector<FurniturePiece>& drawn,
                                       size_t index, Rng& rng) {
  const Place& place = places[index];
  const std::vector<const TrainingFurnitureModel*> candidates = Candidates(place);
  const TrainingFurnitureModel& model =
      *candidates[std::uniform_int_distribution<size_t>(0, candidates.size() - 1)(rng)];
  const Jitter jitter = JitterOf(place.group, place.support.has_value());
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const double yaw = jitter.yaw_deg * unit(rng);
  const double radius = jitter.move_m * std::sqrt(0.5 * (1.0 + unit(rng)));
  const Eigen::Vector2d move = Rotated({radius, 0.0}, 180.0 * unit(rng));
  FurniturePiece piece;
  if (place.support) {
    piece = OnSupport(place, places[*place.support], drawn[*place.support], move, yaw);
  } else {
    piece = place.piece;
    piece.position_m += move;
    piece.yaw_deg += yaw;
    if (place.group == "wall") piece.elevation_m += 0.1 * unit(rng);
  }
  piece.model = model.model;
  if (!place.support && !FitToRoom(place, model.size_m, &piece)) return std::nullopt;
  return piece;
}

// The place's piece: the first acceptable draw, else its default piece (on
// its drawn support).
FurniturePiece DrawPlace(const std::vector<Place>& places, const std::vector<FurniturePiece>& drawn,
                         size_t index, const std::vector<RouteWaypoint>& route, Rng& rng) {
  const Place& place = places[index];
  for (int t = 0; t < kTries; ++t) {
    const std::optional<FurniturePiece> piece = DrawOnce(places, drawn, index, rng);
    if (piece && Acceptable(places, *piece, drawn, index, route)) return *piece;
  }
  if (!place.support) return place.piece;
  FurniturePiece piece = OnSupport(place, places[*place.support], drawn[*place.support], {0.0, 0.0}, 0.0);
  piece.model = place.piece.model;
  return piece;
}

double PointSegmentDistance(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double length2 = ab.squaredNorm();
  const double t = length2 > 0.0 ? std::clamp((p - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
  return (p - (a + t * ab)).norm();
}

double Cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

bool SegmentsCross(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                   const Eigen::Vector2d& d) {
  const double d1 = Cross(b - a, c - a), d2 = Cross(b - a, d - a);
  const double d3 = Cross(d - c, a - c), d4 = Cross(d - c, b - c);
  return ((d1 > 0) != (d2 > 0)) && ((d3 > 0) != (d4 > 0));
}

double SegmentDistance(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                       const Eigen::Vector2d& d) {
  if (SegmentsCross(a, b, c, d)) return 0.0;
  return std::min({PointSegmentDistance(a, c, d), PointSegmentDistance(b, c, d), PointSegmentDistance(c, a, b),
                   PointSegmentDistance(d, a, b)});
}

}  // namespace

const std::vector<TrainingFurnitureModel>& TrainingFurnitureModels() {
  // BlendSwap-CC-0.sh3f's sizes (width#N, depth#N, height#N), in metres.
  static const std::vector<TrainingFurnitureModel> kModels = {
      {"seat", "sofa2", {1.669, 0.747, 0.848}}, {"seat", "couch", {2.074, 0.876, 0.856}},
      {"seat", "modernArmchair", {0.773, 0.849, 0.865}}, {"seat", "armchair2", {0.953, 0.833, 0.783}},
      {"seat", "winchesterArmchair", {1.12, 0.934, 0.804}},
      {"storage", "televisionCabinet", {1.354, 0.693, 1.6}}, {"storage", "bookcase", {0.919, 0.365, 1.472}},
      {"storage", "shelves", {0.79, 0.394, 0.79}}, {"storage", "cupboard", {1.005, 0.39, 1.5}},
      {"storage", "verticalShelves", {0.44, 0.39, 1.85}}, {"storage", "desk", {1.393, 0.543, 1.054}},
      {"storage", "drawersCabinet", {0.6, 0.612, 0.885}}, {"storage", "lowerCabinet", {0.6, 0.612, 0.885}},
      {"storage", "bedsideTable2", {0.4855, 0.481, 0.454}},
      {"storage", "wardrobeWithSlidingDoors", {2.0, 0.66, 2.364}}, {"storage", "highCabinet", {0.6, 0.612, 2.17}},
      {"bed", "bedWithTexture", {1.98, 2.2636, 0.765}}, {"bed", "bed1", {1.407, 2.08, 0.955}},
      {"bed", "bed2", {1.447, 2.137, 1.077}}, {"bed", "bed3", {2.022, 2.282, 1.142}},
      {"table", "oakTable", {1.24, 1.24, 0.741}}, {"table", "tableWithTablecloth", {0.803, 0.812, 0.75}},
      {"chair", "chair", {0.513, 0.531, 0.8}}, {"chair", "chair2", {0.403, 0.489, 0.868}},
      {"chair", "plasticChair", {0.444, 0.584, 0.82}}, {"chair", "sillaBlanca", {0.505, 0.584, 0.85}},
      {"chair", "osakaChair", {0.475, 0.525, 0.77}}, {"chair", "thonet", {0.547, 0.577, 0.754}},
      {"chair", "chairWithCushion", {0.441, 0.441, 0.948}}, {"chair", "antiqueChair", {0.498, 0.632, 0.982}},
      {"chair", "oakChair", {0.491, 0.612, 1.178}}, {"chair", "stool2", {0.361, 0.361, 0.78}},
      {"floor", "plant", {0.818, 0.69, 1.171}}, {"floor", "decorativePlant", {0.559, 0.602, 1.031}},
      {"floor", "augalas", {0.609, 0.349, 0.315}}, {"floor", "orchids", {0.311, 0.353, 0.574}},
      {"floor", "electricGuitar", {0.345, 0.321, 1.1}}, {"floor", "basketball", {0.238, 0.238, 0.238}},
      {"floor", "speaker3", {0.221, 0.254, 0.551}}, {"floor", "speaker2", {0.221, 0.254, 0.354}},
      {"floor", "umbrellaFolded", {0.358, 0.357, 0.8}}, {"floor", "bootie", {0.2099, 0.268, 0.1745}},
      {"floor", "slippers", {0.237, 0.281, 0.061}}, {"floor", "caballito", {0.6765, 0.291, 0.498}},
      {"floor", "dustbin", {0.233, 0.233, 0.35}}, {"floor", "tableFan", {0.271, 0.218, 0.401}},
      {"floor", "fireExtinguisher", {0.311, 0.18, 0.623}}, {"floor", "crate", {0.6, 0.589, 0.594}},
      {"floor", "teddyBear", {0.331, 0.218, 0.322}}, {"floor", "briefcase", {0.4, 0.104, 0.333}},
      {"floor", "chicken", {0.242, 0.328, 0.456}},
      {"surface", "headphones", {0.189, 0.2, 0.082}}, {"surface", "kalender", {0.12, 0.079, 0.108}},
      {"surface", "littlePlant", {0.266, 0.266, 0.232}}, {"surface", "coffeeBrewer", {0.134, 0.385, 0.272}},
      {"surface", "kitchenaid", {0.214, 0.36, 0.353}}, {"surface", "bread", {0.216, 0.147, 0.076}},
      {"surface", "knifeStandSwap", {0.3915, 0.035, 0.356}}, {"surface", "tetrapak", {0.0955, 0.095, 0.265}},
      {"surface", "yogurtBottle", {0.0685, 0.0685, 0.212}}, {"surface", "plasticCup", {0.079, 0.079, 0.1}},
      {"surface", "handbag", {0.261, 0.124, 0.194}}, {"surface", "desklamp", {0.244, 0.244, 0.4}},
      {"surface", "teddyBear", {0.331, 0.218, 0.322}}, {"surface", "butter", {0.16, 0.075, 0.034}},
      {"surface", "caffe_final", {0.1, 0.1, 0.043}}, {"surface", "cartoon_biplane", {0.138, 0.124, 0.057}},
      {"surface", "cosmeticsPot", {0.077, 0.078, 0.071}}, {"surface", "mamadeira", {0.05, 0.05, 0.147}},
      {"surface", "beerGlass", {0.154, 0.102, 0.165}}, {"surface", "cupcake", {0.059, 0.0593, 0.0753}},
      {"surface", "hotDog", {0.211, 0.073, 0.065}}, {"surface", "JapaneseLantern", {0.156, 0.156, 0.351}},
      {"surface", "cactus", {0.148, 0.128, 0.225}}, {"surface", "deer", {0.046, 0.1, 0.2}},
      {"surface", "woodToy", {0.077, 0.06, 0.117}}, {"surface", "lockedLocker", {0.2, 0.22, 0.4}},
      {"surface", "speaker2", {0.221, 0.254, 0.354}}, {"surface", "iphone", {0.058, 0.115, 0.009}},
      {"wall", "cuckooClock", {0.266, 0.177, 0.738}}, {"wall", "wallLight", {0.228, 0.246, 0.538}},
      {"wall", "emergencySign", {0.3, 0.035, 0.09}}, {"wall", "towel3", {0.596, 0.081, 0.478}},
  };
  return kModels;
}

Eigen::Vector3d TrainingFurnitureSize(const std::string& model) {
  for (const TrainingFurnitureModel& m : TrainingFurnitureModels()) {
    if (m.model == model) return m.size_m;
  }
  SLAM_CHECK_MSG(false, ("'" + model + "' is not a training furniture model").c_str());
  return Eigen::Vector3d::Zero();
}

Eigen::Vector2d FootprintHalfExtentsM(const FurniturePiece& piece, const Eigen::Vector3d& size_m) {
  const double a = piece.yaw_deg * kPi / 180.0;
  const double c = std::abs(std::cos(a)), s = std::abs(std::sin(a));
  return {0.5 * (c * size_m.x() + s * size_m.y()), 0.5 * (s * size_m.x() + c * size_m.y())};
}

double RouteClearanceM(const FurniturePiece& piece, const Eigen::Vector3d& size_m,
                       const std::vector<RouteWaypoint>& route) {
  std::array<Eigen::Vector2d, 4> corners;
  const double hw = 0.5 * size_m.x(), hd = 0.5 * size_m.y();
  const std::array<Eigen::Vector2d, 4> local = {Eigen::Vector2d(-hw, -hd), Eigen::Vector2d(hw, -hd),
                                                Eigen::Vector2d(hw, hd), Eigen::Vector2d(-hw, hd)};
  for (size_t i = 0; i < 4; ++i) corners[i] = piece.position_m + Rotated(local[i], piece.yaw_deg);
  double best = std::numeric_limits<double>::infinity();
  for (size_t k = 0; k + 1 < route.size(); ++k) {
    const Eigen::Vector2d& a = route[k].position_xy;
    const Eigen::Vector2d& b = route[k + 1].position_xy;
    const Eigen::Vector2d in_box = Rotated(a - piece.position_m, -piece.yaw_deg);
    if (std::abs(in_box.x()) <= hw && std::abs(in_box.y()) <= hd) return 0.0;
    for (size_t i = 0; i < 4; ++i) best = std::min(best, SegmentDistance(a, b, corners[i], corners[(i + 1) % 4]));
  }
  return best;
}

std::vector<FurniturePiece> DrawTrainingFurniture(uint64_t seed) {
  static const std::vector<Place> places = DefaultPlaces();
  const std::vector<RouteWaypoint> route = ApartmentPatrolRoute();
  Rng rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<FurniturePiece> drawn(places.size());
  std::vector<bool> kept(places.size(), true);
  for (size_t i = 0; i < places.size(); ++i) {
    drawn[i] = DrawPlace(places, drawn, i, route, rng);
    const bool small = places[i].group == "floor" || places[i].group == "surface";
    kept[i] = !(small && unit(rng) < kDropSmall);
  }
  std::vector<FurniturePiece> pieces;
  for (size_t i = 0; i < places.size(); ++i) {
    if (kept[i]) pieces.push_back(drawn[i]);
  }
  return pieces;
}

}  // namespace duskmap
