// JSON codec of a TUM-layout session's calibration file (calibration.json,
// slam/core/json_codec.h): every key required, the intrinsics flat beside the
// depth scale:
//   {"width": 640, "height": 480, "fx": 525, "fy": 525, "cx": 319.5, "cy": 239.5,
//    "depth_scale": 1000}
#pragma once

#include "slam/core/json_codec.h"
#include "slam/io/calibration.h"

namespace duskmap {

template <>
struct JsonCodec<TumCalibration> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    f("width", o.camera.width, JsonRequired{});
    f("height", o.camera.height, JsonRequired{});
    f("fx", o.camera.fx, JsonRequired{});
    f("fy", o.camera.fy, JsonRequired{});
    f("cx", o.camera.cx, JsonRequired{});
    f("cy", o.camera.cy, JsonRequired{});
    f("depth_scale", o.depth_scale, JsonRequired{});
  }
};

}  // namespace duskmap
