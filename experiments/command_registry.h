// Subcommands of the `duskmap` program register themselves here, one file per
// command under experiments/commands/. A command parses straight into an
// options struct, calls the library and returns an exit code; it holds no
// algorithm code.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace duskmap::cli {

// Runs a parsed command and returns the process exit code.
using RunFn = std::function<int()>;
// Adds the command's options (and nested subcommands) to `command` and returns
// the function that runs it; option storage is captured by the returned
// function (typically through a shared_ptr).
using SetupFn = std::function<RunFn(CLI::App& command)>;

struct CommandSpec {
  std::string name;
  std::string description;
  SetupFn setup;
};

// Called from a static initializer in each command file:
//   const bool kRegistered = RegisterCommand({"generate", "...", &SetupGenerate});
bool RegisterCommand(CommandSpec spec);
const std::vector<CommandSpec>& RegisteredCommands();

// Whether stdout is an interactive terminal (live progress lines vs plain logs).
bool StdoutIsTerminal();

}  // namespace duskmap::cli
