// Benchmark support: where the bench binaries write. Scratch files of one
// bench process lie under <system temp>/duskmap_bench_<pid>/, removed when the
// process exits (tests/testing/temp_dir.h's scratch root; DUSKMAP_KEEP_BENCH_TMP=1
// keeps them). Data kept across runs on purpose has its own path
// (BenchCachePath).
#pragma once

#include <filesystem>
#include <string>

#include "tests/testing/temp_dir.h"

namespace duskmap::bench {

namespace internal {

inline const testing::internal::ProcessScratchRoot& ScratchRoot() {
  static const testing::internal::ProcessScratchRoot root("duskmap_bench_",
                                                          "DUSKMAP_KEEP_BENCH_TMP");
  return root;
}

}  // namespace internal

// An empty folder named `stem` under this process's scratch root, made anew
// on each call with the same stem.
inline std::string BenchTempDir(const std::string& stem) { return internal::ScratchRoot().Dir(stem); }

// A path for a file named `name` under this process's scratch root (the file
// itself is not made).
inline std::string BenchTempPath(const std::string& name) {
  return internal::ScratchRoot().Path(name);
}

// <system temp>/<name>, which outlives the process: data a bench makes once
// and reuses in later runs (engine_bench's generated dataset), never removed
// here.
inline std::string BenchCachePath(const std::string& name) {
  return (std::filesystem::temp_directory_path() / name).string();
}

}  // namespace duskmap::bench
