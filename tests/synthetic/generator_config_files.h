// Generator configs written as files for tests that read them through
// ReadGeneratorConfig, and the one-line error reading one gives.
#pragma once

#include <fstream>
#include <string>

#include "slam/core/check.h"
#include "slam/synthetic/generator_config.h"
#include "tests/testing/temp_dir.h"

namespace duskmap::testing {

// Writes `text` to a file of this test process named after `name`; returns its path.
inline std::string WriteGeneratorConfig(const std::string& name, const std::string& text) {
  const std::string path = ProcessTempPath("cfg_" + name + ".json");
  std::ofstream(path) << text;
  return path;
}

// The ConfigError's message reading `path` gives, or "" when it reads.
inline std::string GeneratorConfigError(const std::string& path) {
  try {
    ReadGeneratorConfig(path);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

}  // namespace duskmap::testing
