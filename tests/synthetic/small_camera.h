// The 160 x 120 pinhole camera the renderer tests draw with (the default
// 640 x 480 camera scaled by 1/4).
#pragma once

#include "slam/core/camera.h"

namespace duskmap {

inline PinholeCamera SmallCamera() {
  PinholeCamera c;
  c.width = 160;
  c.height = 120;
  c.fx = c.fy = 131.25;
  c.cx = 79.5;
  c.cy = 59.5;
  return c;
}

}  // namespace duskmap
