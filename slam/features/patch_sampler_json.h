// JSON codec of PatchSamplerOptions (patch_sampler.h; slam/core/json_codec.h):
//   {"patch_size_px": 32, "support_per_size": 6.0, "oriented": true}
#pragma once

#include "slam/core/json_codec.h"
#include "slam/features/patch_sampler.h"

namespace duskmap {

template <>
struct JsonCodec<PatchSamplerOptions> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    f("patch_size_px", o.patch_size_px);
    f("support_per_size", o.support_per_size);
    f("oriented", o.oriented);
  }
};

}  // namespace duskmap
