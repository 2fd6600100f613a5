// Writing one image file, with the system's reason on failure: OpenCV's
// imwrite only says false (and libpng prints its own line to stderr), so a
// full disk read "cannot write image" with a stray "libpng error". The image
// is encoded in memory by its extension, then written and closed with every
// error checked.
#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace duskmap {

// Encodes `image` by the extension of `path` (".png", ".jpg", ...) with
// OpenCV's `params` (the bytes cv::imwrite would write) and writes it to
// `path`. Throws InputError "<path>: cannot write image: <reason>" when the
// file cannot be created, written or closed (a partial file is removed), and
// "<path>: cannot encode image" when OpenCV refuses the image.
void WriteImageFile(const std::string& path, const cv::Mat& image,
                    const std::vector<int>& params = {});

}  // namespace duskmap
