// The JSON codec of the training scenes' options (slam/core/json_codec.h):
//   {"seed": 20261207, "scenes": 10, "hours_per_scene": 4, "frames_per_hour": 96}
// Every key is optional (absent keys keep the defaults of training_scenes.h).
#pragma once

#include "slam/core/json_codec.h"
#include "slam/synthetic/training_scenes.h"

namespace duskmap {

template <>
struct JsonCodec<TrainingScenesOptions> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    f("seed", o.seed);
    f("scenes", o.scenes);
    f("hours_per_scene", o.hours_per_scene);
    f("frames_per_hour", o.frames_per_hour);
  }
};

}  // namespace duskmap
