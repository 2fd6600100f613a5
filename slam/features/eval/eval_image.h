// The images of the feature benchmarks (`duskmap features eval`): homography
// sequences and WxBS-style pairs read the same way.
#pragma once

#include <string>

#include <opencv2/core.hpp>

namespace duskmap {

// The image at `path` as 8-bit BGR; InputError naming the path when it
// cannot be read or decoded.
cv::Mat ReadEvalImage(const std::string& path);

}  // namespace duskmap
