#include "slam/core/input_file.h"

#include <sys/stat.h>

#include <cerrno>
#include <cstring>

#include "slam/core/check.h"

namespace duskmap {
namespace {

// What a non-regular file is, in words.
const char* KindOf(mode_t mode) {
  if (S_ISDIR(mode)) return "a folder";
  if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
  if (S_ISSOCK(mode)) return "a socket";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  return "a special file";
}

}  // namespace

void RefuseNonRegularFile(const std::string& path, const std::string& flag) {
  const std::string name = flag.empty() ? path : flag + " " + path;
  struct stat info;
  if (::stat(path.c_str(), &info) != 0) {
    const int error = errno;
    SLAM_THROW_IF_NOT(InputError, error == ENOENT || error == ENOTDIR)
        << name << ": " << std::strerror(error);
    return;  // missing: the reader names it
  }
  SLAM_THROW_IF_NOT(InputError, S_ISREG(info.st_mode))
      << name << ": is " << KindOf(info.st_mode) << ", not a regular file";
}

}  // namespace duskmap
