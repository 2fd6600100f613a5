// JSON codecs of the training data's options (training_data_options.h;
// slam/core/json_codec.h): the "data" section of configs/dusknet.json
//   {"scenes": {"seed": 20261207, "scenes": 10, "hours_per_scene": 4, "frames_per_hour": 48},
//    "patch": {"patch_size_px": 32, "support_per_size": 6.0, "oriented": true},
//    "max_pairs_per_image_pair": 48, "max_offset_px": 2.0, ...}
#pragma once

#include "slam/core/json_codec.h"
#include "slam/features/patch_sampler_json.h"
#include "slam/synthetic/training_scenes_json.h"
#include "slam/training/training_data_options.h"

namespace duskmap {

template <>
struct JsonCodec<TrainingDataOptions> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    f("scenes", o.scenes);
    f("patch", o.patch);
    f("max_pairs_per_image_pair", o.max_pairs_per_image_pair);
    f("max_offset_px", o.max_offset_px);
    f("max_scale_ratio", o.max_scale_ratio);
    f("max_angle_deg", o.max_angle_deg);
    f("occlusion_tolerance", o.occlusion_tolerance);
    f("same_time_share", o.same_time_share);
    f("validation_scenes", o.validation_scenes);
    f("threads", o.threads);
  }
};

}  // namespace duskmap
