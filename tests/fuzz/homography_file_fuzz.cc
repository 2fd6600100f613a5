// libFuzzer target: the homography file reader of `duskmap features eval`'s
// homography layout (ParseHomography, image_sequence.h; ReadHomography reads
// an H<i>to<j>p file and calls it). Any input either throws duskmap::Error,
// one line starting with the file's name, or gives a homography whose nine
// entries and inverse are finite (SelectSequencePairs composes a pair i-j as
// H1toJp * H1toIp^-1) with a non-zero determinant.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include <opencv2/core.hpp>

#include "slam/core/check.h"
#include "slam/features/eval/image_sequence.h"

namespace {

bool Finite(const cv::Matx33d& m) {
  for (const double v : m.val) {
    if (!std::isfinite(v)) return false;
  }
  return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  cv::Matx33d h;
  try {
    h = duskmap::ParseHomography(text, "seq/H1to2p");
  } catch (const duskmap::Error& e) {
    const std::string message = e.what();
    if (message.rfind("seq/H1to2p: ", 0) != 0 || message.find('\n') != std::string::npos) std::abort();
    return 0;
  }
  if (!Finite(h) || !(std::abs(cv::determinant(h)) > 0.0) || !Finite(h.inv())) std::abort();
  return 0;
}
