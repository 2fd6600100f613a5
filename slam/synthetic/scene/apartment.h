// The default furnished apartment (about 90 m2): a living room with windows on
// its west and south walls, an open kitchen, a corridor and a bedroom, with
// furniture, pictures, posters, books and rugs, the docking picture on the
// living-room north wall, and the lamps. Also the patrol route through it.
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "slam/synthetic/scene/furniture_layout.h"
#include "slam/synthetic/scene/photo_materials.h"
#include "slam/synthetic/scene/scene.h"

namespace duskmap {

// Every setting of the apartment's lamps (JSON "scene.lamps").
struct LampOptions {
  double intensity_scale = 1.6;  // multiplies every lamp's candela (tuned for realism)
  std::string living_lamp_on_from = "17:54";  // clock time the living-room floor lamp goes on
  double bedroom_ceiling_cd = 0.0;  // a bedroom ceiling light on in every session; 0 = none
  double living_ceiling_cd = 0.0;   // a living-room ceiling light on in every session; 0 = none
  LampLight light;                  // colour temperature and shade glow (the scene carries them)

  void Check() const;  // throws ConfigError "scene.lamps.<field> ..."
};

struct ApartmentOptions {
  uint64_t seed = 7;           // texture seed
  std::string textures_dir;    // optional folder of images for pictures/posters
  double wall_height_m = 2.5;  // floor to ceiling
  LampOptions lamps;
  // Window glass reflects the room (mirror reflectance at normal incidence,
  // e.g. 0.08 for double glazing): invisible against the daylight sky, the
  // room's mirror image in a dark pane at night. 0 = windows only transmit.
  double window_reflectance = 0.0;
  // The floors' varnish or glaze as a mirror (reflectance at normal
  // incidence, e.g. 0.04), growing towards grazing views; rugs do not
  // reflect. 0 = matte floors.
  double floor_reflectance = 0.0;
  // Multiplies the materials' relief heights (plaster, grain, grout, weave,
  // fins, folds, panels; textures.cc), which the light shows by the direction
  // it comes from (relief.h). 1 = plausible real heights (millimetres to
  // centimetres); 0 = every surface flat (the scene before 2026-12-02).
  double relief_scale = 1.0;
  // 0 = the rooms' own wall paints (the default dataset); otherwise each
  // room's paint, and the bedroom's wallpaper, drawn from this seed among
  // plausible paints (the learned descriptor's training scenes,
  // training_scenes.h).
  uint64_t wall_paint_seed = 0;
  // Catalog furniture (furniture_layout.h); none by default.
  FurnitureOptions furniture;
  // Photographic materials from furniture.catalog's images (wood floors,
  // tiles, the kitchen counter, furniture wood, fabric; photo_materials.h);
  // none by default: every surface procedural.
  std::vector<PhotoMaterialSpec> photo_materials;
  // The furniture drawn as textured boxes: the sofa, TV stand, bookshelves,
  // dining and kitchen tables with their chairs, the bed, bedside table,
  // wardrobe and dresser. False when catalog pieces stand in for them; the
  // fittings (walls, windows, doors, radiators, pictures, rugs, curtains,
  // shelves of objects, lamps) stay either way.
  bool box_furniture = true;

  void Check() const;
};

Scene BuildApartment(const ApartmentOptions& options);

// A room's floor: the rectangle its walls enclose (world x, y, metres).
struct RoomFloor {
  std::string name;  // as in Scene::room_names
  Eigen::Vector2d min_xy = Eigen::Vector2d::Zero();
  Eigen::Vector2d max_xy = Eigen::Vector2d::Zero();
};

// The apartment's rooms, in Scene::room_names order.
std::vector<RoomFloor> ApartmentRoomFloors();

// One waypoint of the patrol route: walk to `position_xy`, then optionally
// hold still or turn in place (positive = counter-clockwise seen from above).
struct RouteWaypoint {
  Eigen::Vector2d position_xy = Eigen::Vector2d::Zero();
  double spin_deg = 0.0;  // in-place rotation after arriving
  double hold_s = 0.0;    // standing still after arriving (after the spin)
  double face_yaw_deg = std::numeric_limits<double>::quiet_NaN();  // turn to face this yaw when set
};

// The patrol route through every room; it starts and ends at the docking view.
std::vector<RouteWaypoint> ApartmentPatrolRoute();

}  // namespace duskmap
