// Test support shared by the suites (tests/testing/): runs the `duskmap`
// program (DUSKMAP_EXE, set for the cli suite) and collects what it prints.
#pragma once

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "slam/synthetic/generator_config.h"

namespace duskmap::testing {

struct CliResult {
  int exit_code = -1;
  std::string output;  // stdout and stderr
};

// `<command> 2>&1` through the shell; exit_code -1 when it did not exit
// normally.
inline CliResult RunShell(const std::string& command) {
  CliResult result;
  FILE* pipe = ::popen((command + " 2>&1").c_str(), "r");
  if (!pipe) return result;
  std::array<char, 4096> buffer;
  while (size_t n = std::fread(buffer.data(), 1, buffer.size(), pipe)) result.output.append(buffer.data(), n);
  const int status = ::pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

// `<prefix>duskmap <args> 2>&1` through the shell (`prefix`: a `cd`, a
// ulimit).
inline CliResult RunDuskmap(const std::string& args, const std::string& prefix = "") {
  return RunShell(prefix + std::string(DUSKMAP_EXE) + " " + args);
}

// Generates the box-furniture apartment (configs/sunset_apartment_boxes.json) with
// `max_frames` frames per session into `dir`/data, through `duskmap generate`:
// the named sessions of the default twelve, at their clock times and roles
// (GeneratorConfig::DefaultSessions).
inline CliResult GenerateSmallApartment(const std::string& dir, int max_frames,
                                        const std::vector<std::string>& session_names) {
  nlohmann::json sessions = nlohmann::json::array();
  for (const std::string& name : session_names) {
    bool found = false;
    for (const SessionSpec& s : GeneratorConfig::DefaultSessions()) {
      if (s.name != name) continue;
      sessions.push_back({{"name", s.name}, {"clock_time", s.clock_time}, {"role", s.role}});
      found = true;
    }
    if (!found) return {-1, "GenerateSmallApartment: no default session '" + name + "'"};
  }
  nlohmann::json config = nlohmann::json::parse(
      std::ifstream(std::string(DUSKMAP_SOURCE_DIR) + "/configs/sunset_apartment_boxes.json"));
  config["max_frames"] = max_frames;
  config["sessions"] = sessions;
  std::ofstream(dir + "/gen.json") << config.dump();
  return RunDuskmap("generate --config " + dir + "/gen.json --output " + dir + "/data");
}

}  // namespace duskmap::testing
