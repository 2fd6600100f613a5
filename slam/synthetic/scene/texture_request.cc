#include "slam/synthetic/scene/texture_request.h"

#include <algorithm>
#include <cmath>

namespace duskmap {

int TexelCount(double size_m, double texel_m) {
  return std::max(2, static_cast<int>(std::lround(size_m / texel_m)));
}

}  // namespace duskmap
