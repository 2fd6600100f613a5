// Benchmark support: where the bench binaries write. Scratch files of one
// bench process lie under <system temp>/duskmap_bench_<pid>/, removed when the
// process exits (from the process that made it only: a forked child must not
// delete its parent's files), the same idea as tests/testing/temp_dir.h. Data
// kept across runs on purpose has its own path (BenchCachePath).
#pragma once

#include <unistd.h>

#include <filesystem>
#include <string>
#include <system_error>

namespace duskmap::bench {

namespace internal {

class ProcessTempRoot {
 public:
  ProcessTempRoot()
      : owner_(::getpid()),
        path_(std::filesystem::temp_directory_path() / ("duskmap_bench_" + std::to_string(owner_))) {}
  ~ProcessTempRoot() {
    if (::getpid() != owner_) return;
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  ProcessTempRoot(const ProcessTempRoot&) = delete;
  ProcessTempRoot& operator=(const ProcessTempRoot&) = delete;
  const std::filesystem::path& path() const { return path_; }

 private:
  pid_t owner_;
  std::filesystem::path path_;
};

inline const std::filesystem::path& ProcessTempRootPath() {
  static const ProcessTempRoot root;
  return root.path();
}

}  // namespace internal

// An empty folder named `stem` under this process's scratch root, made anew
// on each call with the same stem.
inline std::string BenchTempDir(const std::string& stem) {
  const std::filesystem::path dir = internal::ProcessTempRootPath() / stem;
  std::error_code ignored;
  std::filesystem::remove_all(dir, ignored);
  std::filesystem::create_directories(dir);
  return dir.string();
}

// A path for a file named `name` under this process's scratch root (the file
// itself is not made).
inline std::string BenchTempPath(const std::string& name) {
  std::filesystem::create_directories(internal::ProcessTempRootPath());
  return (internal::ProcessTempRootPath() / name).string();
}

// <system temp>/<name>, which outlives the process: data a bench makes once
// and reuses in later runs (engine_bench's generated dataset), never removed
// here.
inline std::string BenchCachePath(const std::string& name) {
  return (std::filesystem::temp_directory_path() / name).string();
}

}  // namespace duskmap::bench
