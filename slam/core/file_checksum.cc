#include "slam/core/file_checksum.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <algorithm>
#include <cstdio>
#include <vector>

#include "slam/core/check.h"
#include "slam/core/checksum.h"
#include "slam/core/system_error.h"

namespace duskmap {
namespace {

constexpr size_t kBlockBytes = size_t{1} << 20;

// Closes the descriptor on every path out.
class FileDescriptor {
 public:
  explicit FileDescriptor(int fd) : fd_(fd) {}
  ~FileDescriptor() {
    if (fd_ >= 0) ::close(fd_);
  }
  FileDescriptor(const FileDescriptor&) = delete;
  FileDescriptor& operator=(const FileDescriptor&) = delete;
  int get() const { return fd_; }

 private:
  int fd_;
};

}  // namespace

uint64_t FileChecksum64(const std::filesystem::path& path) {
  // O_NONBLOCK: opening a FIFO must not wait for a writer; it is refused below.
  const FileDescriptor fd(::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC));
  SLAM_THROW_IF_NOT(InputError, fd.get() >= 0)
      << path.string() << ": cannot read (" << LastSystemError() << ")";
  struct stat status {};
  SLAM_THROW_IF_NOT(InputError, ::fstat(fd.get(), &status) == 0)
      << path.string() << ": cannot read (" << LastSystemError() << ")";
  SLAM_THROW_IF_NOT(InputError, S_ISREG(status.st_mode))
      << path.string() << ": not a regular file";
  std::vector<unsigned char> block(kBlockBytes);
  std::vector<uint64_t> sums;  // one per block, then the size
  uint64_t total = 0;
  size_t filled = 0;
  while (true) {
    const ssize_t got = ::read(fd.get(), block.data() + filled, block.size() - filled);
    if (got < 0 && errno == EINTR) continue;
    SLAM_THROW_IF_NOT(InputError, got >= 0)
        << path.string() << ": cannot read (" << LastSystemError() << ")";
    filled += static_cast<size_t>(got);
    total += static_cast<uint64_t>(got);
    if (filled == block.size() || (got == 0 && filled > 0)) {
      sums.push_back(Checksum64(block.data(), filled));
      filled = 0;
    }
    if (got == 0) break;
  }
  sums.push_back(total);
  return Checksum64(sums.data(), sums.size() * sizeof(uint64_t));
}

uint64_t BytesChecksum64(const void* data, size_t bytes) {
  const unsigned char* at = static_cast<const unsigned char*>(data);
  std::vector<uint64_t> sums;  // as FileChecksum64: one per block, then the size
  for (size_t done = 0; done < bytes; done += kBlockBytes) {
    sums.push_back(Checksum64(at + done, std::min(kBlockBytes, bytes - done)));
  }
  sums.push_back(bytes);
  return Checksum64(sums.data(), sums.size() * sizeof(uint64_t));
}

std::string FileChecksum64Hex(const std::filesystem::path& path) {
  char text[17];
  std::snprintf(text, sizeof(text), "%016llx",
                static_cast<unsigned long long>(FileChecksum64(path)));
  return text;
}

}  // namespace duskmap
