// Test support shared by the suites (tests/testing/): runs the `duskmap`
// program (DUSKMAP_EXE, set for the cli suite) and collects what it prints.
#pragma once

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace duskmap::testing {

struct CliResult {
  int exit_code = -1;
  std::string output;  // stdout and stderr
};

// `duskmap <args> 2>&1`; exit_code -1 when it did not exit normally.
inline CliResult RunDuskmap(const std::string& args) {
  CliResult result;
  FILE* pipe = ::popen((std::string(DUSKMAP_EXE) + " " + args + " 2>&1").c_str(), "r");
  if (!pipe) return result;
  std::array<char, 4096> buffer;
  while (size_t n = std::fread(buffer.data(), 1, buffer.size(), pipe)) result.output.append(buffer.data(), n);
  const int status = ::pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

}  // namespace duskmap::testing
