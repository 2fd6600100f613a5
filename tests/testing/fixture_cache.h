// Test support shared by the suites (tests/testing/): inputs that are slow to
// make (a rendered dataset) made once per build and shared by every test
// process.
//
// gtest_discover_tests runs each test in its own process, so a fixture made
// "once per process" is made once per test. CachedFixture makes it once: the
// first process that needs it takes an exclusive lock on
// <build>/test_fixtures/<name>.lock, builds into a fresh folder and renames it
// to <build>/test_fixtures/<name>-<stamp>; the others wait on the lock and
// reuse the folder. The stamp is the modification time of the running test
// executable, so a rebuilt test binary (after a change to the code that makes
// the fixture) makes it anew. Fixtures are read-only for the tests: write
// into ProcessTempDir (temp_dir.h) instead.
#pragma once

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <functional>
#include <string>
#include <system_error>

#include "slam/core/check.h"

namespace duskmap::testing {

// The folder of fixture `name`, made by `build(folder)` once per build (see
// above). `build` gets an empty folder that does not exist yet at its final
// path; a failed build leaves nothing and throws again in the next process.
inline std::string CachedFixture(const std::string& name,
                                 const std::function<void(const std::string& folder)>& build) {
  namespace fs = std::filesystem;
  const fs::path root = fs::path(DUSKMAP_BINARY_DIR) / "test_fixtures";
  fs::create_directories(root);
  const auto stamp = fs::last_write_time("/proc/self/exe").time_since_epoch();
  const std::string stem = name + "-";
  const fs::path folder =
      root / (stem + std::to_string(std::chrono::duration_cast<std::chrono::seconds>(stamp).count()));
  if (fs::exists(folder)) return folder.string();
  const std::string lock_path = (root / (name + ".lock")).string();
  const int fd = ::open(lock_path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  SLAM_CHECK_MSG(fd >= 0, "cannot open the fixture lock");
  SLAM_CHECK_MSG(::flock(fd, LOCK_EX) == 0, "cannot lock the fixture lock");
  if (!fs::exists(folder)) {  // not made while this process waited
    std::error_code ignored;
    for (const fs::directory_entry& entry : fs::directory_iterator(root)) {
      const std::string entry_name = entry.path().filename().string();
      if (entry_name.rfind(stem, 0) == 0) fs::remove_all(entry.path(), ignored);  // other builds', partial ones
    }
    const fs::path partial = root / (stem + "partial-" + std::to_string(::getpid()));
    try {
      build(partial.string());
      fs::rename(partial, folder);
    } catch (...) {
      fs::remove_all(partial, ignored);
      ::close(fd);
      throw;
    }
  }
  ::close(fd);  // releases the lock
  return folder.string();
}

}  // namespace duskmap::testing
