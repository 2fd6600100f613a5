// Checks the CLI suites share (tests/cli/): the one-line error every bad
// input must give, and files' bytes before and after a command, for the
// cases where a file must survive.
#pragma once

#include <algorithm>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/testing/read_text.h"
#include "tests/testing/run_duskmap.h"

namespace duskmap::testing {

// One line that starts "duskmap: error: ", exit code 1 (a crash exits -1),
// and each needle in it.
inline void ExpectOneLineError(const CliResult& r, const std::vector<std::string>& needles) {
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_EQ(r.output.rfind("duskmap: error: ", 0), 0u) << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  for (const std::string& needle : needles) {
    EXPECT_NE(r.output.find(needle), std::string::npos) << "missing '" << needle << "' in " << r.output;
  }
}

// Every file under `root` (or `root` itself) with its bytes.
inline std::map<std::string, std::string> Snapshot(const std::filesystem::path& root) {
  std::map<std::string, std::string> files;
  if (std::filesystem::is_regular_file(root)) {
    files[root.string()] = ReadText(root);
    return files;
  }
  for (const auto& entry : std::filesystem::recursive_directory_iterator(root)) {
    if (entry.is_regular_file()) files[entry.path().string()] = ReadText(entry.path());
  }
  return files;
}

}  // namespace duskmap::testing
