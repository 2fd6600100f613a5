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

// Removes the process's temporary root at exit, from the process that made it
// only (a forked child that exits normally must not delete its parent's files).
class ProcessTempRoot {
 public:
  ProcessTempRoot()
      : owner_(::getpid()),
        path_(std::filesystem::temp_directory_path() / ("duskmap_tests_" + std::to_string(owner_))) {}
  ~ProcessTempRoot() {
    if (::getpid() != owner_ || std::getenv("DUSKMAP_KEEP_TEST_TMP") != nullptr) return;
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

// An empty folder named after `stem` under this process's temporary root,
// made anew on each call with the same stem.
inline std::string ProcessTempDir(const std::string& stem) {
  namespace fs = std::filesystem;
  const fs::path dir = internal::ProcessTempRootPath() / stem;
  std::error_code ignored;
  fs::remove_all(dir, ignored);
  fs::create_directories(dir);
  return dir.string();
}

// A path for a file named `name` under this process's temporary root (the
// file itself is not made).
inline std::string ProcessTempPath(const std::string& name) {
  namespace fs = std::filesystem;
  fs::create_directories(internal::ProcessTempRootPath());
  return (internal::ProcessTempRootPath() / name).string();
}

}  // namespace duskmap::testing
