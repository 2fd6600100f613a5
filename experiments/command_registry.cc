#include "experiments/command_registry.h"

#include <unistd.h>

#include <algorithm>

namespace duskmap::cli {
namespace {
std::vector<CommandSpec>& Registry() {
  static std::vector<CommandSpec> commands;
  return commands;
}
}  // namespace

bool RegisterCommand(CommandSpec spec) {
  Registry().push_back(std::move(spec));
  std::sort(Registry().begin(), Registry().end(),
            [](const CommandSpec& a, const CommandSpec& b) { return a.name < b.name; });
  return true;
}

const std::vector<CommandSpec>& RegisteredCommands() { return Registry(); }

bool StdoutIsTerminal() { return isatty(STDOUT_FILENO) == 1; }

}  // namespace duskmap::cli
