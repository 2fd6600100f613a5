#include "slam/io/image_file.h"

#include <cerrno>
#include <cstdio>
#include <cstring>

#include <opencv2/imgcodecs.hpp>

#include "slam/core/check.h"

namespace duskmap {

void WriteImageFile(const std::string& path, const cv::Mat& image, const std::vector<int>& params) {
  const size_t dot = path.rfind('.');
  SLAM_THROW_IF_NOT(InputError, dot != std::string::npos && path.find('/', dot) == std::string::npos)
      << path << ": cannot encode image: no file extension";
  std::vector<unsigned char> bytes;
  bool encoded = false;
  try {
    encoded = cv::imencode(path.substr(dot), image, bytes, params);
  } catch (const cv::Exception& e) {
    SLAM_THROW(InputError) << path << ": cannot encode image: " << e.err;
  }
  SLAM_THROW_IF_NOT(InputError, encoded) << path << ": cannot encode image";
  std::FILE* file = std::fopen(path.c_str(), "wb");
  SLAM_THROW_IF_NOT(InputError, file != nullptr)
      << path << ": cannot write image: " << std::strerror(errno);
  int failure = 0;
  errno = 0;  // a short write's reason is the system's only if a call set it here
  if (std::fwrite(bytes.data(), 1, bytes.size(), file) != bytes.size()) failure = errno ? errno : EIO;
  if (std::fclose(file) != 0 && failure == 0) failure = errno ? errno : EIO;
  if (failure != 0) {
    std::remove(path.c_str());
    SLAM_THROW(InputError) << path << ": cannot write image: " << std::strerror(failure);
  }
}

}  // namespace duskmap
