// Test support shared by the suites (tests/testing/): runs the `duskmap`
// program (DUSKMAP_EXE, set for the cli suite) and collects what it prints.
#pragma once

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

namespace duskmap::testing {

struct CliResult {
  int exit_code = -1;
  std::string output;  // stdout and stderr
};

// `<prefix>duskmap <args> 2>&1` through the shell (`prefix`: a `cd`, a
// ulimit); exit_code -1 when it did not exit normally.
inline CliResult RunDuskmap(const std::string& args, const std::string& prefix = "") {
  CliResult result;
  FILE* pipe = ::popen((prefix + std::string(DUSKMAP_EXE) + " " + args + " 2>&1").c_str(), "r");
  if (!pipe) return result;
  std::array<char, 4096> buffer;
  while (size_t n = std::fread(buffer.data(), 1, buffer.size(), pipe)) result.output.append(buffer.data(), n);
  const int status = ::pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

// Generates the box-furniture apartment (configs/sunset_apartment_boxes.json) with
// `max_frames` frames per session and the given sessions (objects with name,
// clock_time, role) into `dir`/data, through `duskmap generate`.
inline CliResult GenerateSmallApartment(const std::string& dir, int max_frames,
                                        const nlohmann::json& sessions) {
  nlohmann::json config = nlohmann::json::parse(
      std::ifstream(std::string(DUSKMAP_SOURCE_DIR) + "/configs/sunset_apartment_boxes.json"));
  config["max_frames"] = max_frames;
  config["sessions"] = sessions;
  std::ofstream(dir + "/gen.json") << config.dump();
  return RunDuskmap("generate --config " + dir + "/gen.json --output " + dir + "/data");
}

}  // namespace duskmap::testing
