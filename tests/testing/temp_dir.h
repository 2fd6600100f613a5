// Test support (tests/testing/): temporary folders that belong to one test
// process and are removed when it exits.
//
// Every folder lies under <system temp>/duskmap_tests_<pid>/, so two test
// processes never share one, and the whole root is removed at normal exit of
// the process that made it (gtest_discover_tests runs one test per process, so
// after each test). Set DUSKMAP_KEEP_TEST_TMP=1 to keep them for debugging; a
// crashed process leaves its root behind, named by its pid.
#pragma once

#include <sys/stat.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>

namespace duskmap::testing {

namespace internal {

// A process's scratch root, <system temp>/<prefix><pid>/, removed at exit by
// the process that made it only (a forked child that exits normally must not
// delete its parent's files), unless the environment variable `keep_env` is
// set. The benches use it too (bench/bench_temp_dir.h).
class ProcessScratchRoot {
 public:
  ProcessScratchRoot(const std::string& prefix, const char* keep_env)
      : owner_(::getpid()),
        keep_env_(keep_env),
        path_(std::filesystem::temp_directory_path() / (prefix + std::to_string(owner_))) {}
  ~ProcessScratchRoot() {
    if (::getpid() != owner_ || std::getenv(keep_env_) != nullptr) return;
    namespace fs = std::filesystem;
    std::error_code ignored;
    if (!fs::exists(path_, ignored)) return;
    // Tests make folders read-only on purpose: give them back write permission first.
    for (auto it = fs::recursive_directory_iterator(path_, fs::directory_options::skip_permission_denied, ignored);
         it != fs::recursive_directory_iterator(); it.increment(ignored)) {
      if (it->is_directory(ignored) && !it->is_symlink(ignored)) {
        fs::permissions(it->path(), fs::perms::owner_all, fs::perm_options::add, ignored);
      }
    }
    fs::permissions(path_, fs::perms::owner_all, fs::perm_options::add, ignored);
    fs::remove_all(path_, ignored);
  }
  ProcessScratchRoot(const ProcessScratchRoot&) = delete;
  ProcessScratchRoot& operator=(const ProcessScratchRoot&) = delete;
  const std::filesystem::path& path() const { return path_; }

  // An empty folder named `stem` under the root, made anew on each call.
  std::string Dir(const std::string& stem) const {
    namespace fs = std::filesystem;
    const fs::path dir = path_ / stem;
    std::error_code ignored;
    fs::remove_all(dir, ignored);
    fs::create_directories(dir);
    return dir.string();
  }
  // A path for a file named `name` under the root (the file is not made).
  std::string Path(const std::string& name) const {
    std::filesystem::create_directories(path_);
    return (path_ / name).string();
  }

 private:
  pid_t owner_;
  const char* keep_env_;
  std::filesystem::path path_;
};

inline const ProcessScratchRoot& ProcessTempRoot() {
  static const ProcessScratchRoot root("duskmap_tests_", "DUSKMAP_KEEP_TEST_TMP");
  return root;
}

}  // namespace internal

// An empty folder named after `stem` under this process's temporary root,
// made anew on each call with the same stem.
inline std::string ProcessTempDir(const std::string& stem) {
  return internal::ProcessTempRoot().Dir(stem);
}

// A path for a file named `name` under this process's temporary root (the
// file itself is not made).
inline std::string ProcessTempPath(const std::string& name) {
  return internal::ProcessTempRoot().Path(name);
}

}  // namespace duskmap::testing
