// Two error channels (see docs/architecture.md):
//  - bad configuration or bad input at an API boundary throws duskmap::Error
//    (or a subclass) through SLAM_THROW_IF_NOT / SLAM_THROW; the CLI prints its one-line
//    message and exits non-zero;
//  - a broken internal invariant aborts through SLAM_CHECK.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <stdexcept>
#include <string>

namespace duskmap {

// Base of every error the library reports to its caller. The message is one
// line that names the offending file, key or object and the problem.
class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

// A configuration value or file that is malformed or inconsistent.
class ConfigError : public Error {
 public:
  using Error::Error;
};

// Input data (images, sequences, map files) that cannot be read or used.
class InputError : public Error {
 public:
  using Error::Error;
};

namespace internal {
[[noreturn]] inline void AbortCheck(const char* file, int line, const char* expr,
                                    const std::string& message) {
  std::fprintf(stderr, "%s:%d: check failed: %s %s\n", file, line, expr, message.c_str());
  std::abort();
}

// Collects a message with operator<< and throws it as ErrorT when destroyed.
template <typename ErrorT>
class ThrowStream {
 public:
  ThrowStream() = default;
  ThrowStream(const ThrowStream&) = delete;
  ThrowStream& operator=(const ThrowStream&) = delete;
  ~ThrowStream() noexcept(false) { throw ErrorT(stream_.str()); }
  template <typename T>
  ThrowStream& operator<<(const T& value) {
    stream_ << value;
    return *this;
  }

 private:
  std::ostringstream stream_;
};
}  // namespace internal

}  // namespace duskmap

// Aborts when an internal invariant does not hold.
#define SLAM_CHECK(cond)                                                     \
  do {                                                                       \
    if (!(cond)) ::duskmap::internal::AbortCheck(__FILE__, __LINE__, #cond, ""); \
  } while (false)

#define SLAM_CHECK_MSG(cond, msg)                                               \
  do {                                                                          \
    if (!(cond)) ::duskmap::internal::AbortCheck(__FILE__, __LINE__, #cond, (msg)); \
  } while (false)

// Throws ErrorT with the streamed message when cond is false:
//   SLAM_THROW_IF_NOT(ConfigError, x > 0) << path << ": x must be > 0, got " << x;
#define SLAM_THROW_IF_NOT(ErrorT, cond) \
  if (cond) {                           \
  } else                                \
    ::duskmap::internal::ThrowStream<::duskmap::ErrorT>()

#define SLAM_THROW(ErrorT) ::duskmap::internal::ThrowStream<::duskmap::ErrorT>()
