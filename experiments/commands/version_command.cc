// `duskmap version`: prints the program and library versions it was built with.
#include <iostream>

#include <opencv2/core/version.hpp>

#include "experiments/command_registry.h"

namespace duskmap::cli {
namespace {

RunFn SetupVersion(CLI::App& /*command*/) {
  return [] {
    std::cout << "duskmap " << DUSKMAP_VERSION << " (OpenCV " << CV_VERSION << ")\n";
    return 0;
  };
}

const bool kRegistered =
    RegisterCommand({"version", "Print the duskmap version and its libraries", &SetupVersion});

}  // namespace
}  // namespace duskmap::cli
