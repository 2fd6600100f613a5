// `duskmap features training-data` (wired into `features` by features_command.cc).
#pragma once

#include <CLI/CLI.hpp>

#include "experiments/command_registry.h"

namespace duskmap::cli {

// Adds the subcommand to `features` and returns it with the function that runs it.
std::pair<CLI::App*, RunFn> AddTrainingDataCommand(CLI::App& features);

}  // namespace duskmap::cli
