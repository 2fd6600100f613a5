// The system's reason for the last failed call, for error messages: "No space
// left on device" where a stream only says it failed.
#pragma once

#include <cerrno>
#include <cstring>
#include <string>

namespace duskmap {

// strerror(errno), or a plain "no reason given" when errno is 0 (a stream
// that failed without a system call failing, e.g. a formatting error).
inline std::string LastSystemError() {
  const int error = errno;
  return error != 0 ? std::string(std::strerror(error)) : std::string("no reason given");
}

}  // namespace duskmap
