// The `duskmap` command-line program: one binary, one subcommand per job.
#include <exception>
#include <iostream>
#include <map>

#include "experiments/command_registry.h"
#include "slam/core/check.h"

int main(int argc, char** argv) {
  using duskmap::cli::RunFn;
  CLI::App app{
      "duskmap: benchmark and evaluation harness for illumination-invariant visual "
      "re-localization"};
  app.require_subcommand(1);
  std::map<const CLI::App*, RunFn> runners;
  for (const auto& spec : duskmap::cli::RegisteredCommands()) {
    CLI::App* command = app.add_subcommand(spec.name, spec.description);
    runners[command] = spec.setup(*command);
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const std::exception& e) {
    std::cerr << "duskmap: error: " << e.what() << "\n";
    return 2;
  }
  try {
    for (const auto& [command, run] : runners) {
      if (command->parsed()) return run();
    }
  } catch (const duskmap::Error& e) {
    std::cerr << "duskmap: error: " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "duskmap: internal error: " << e.what() << "\n";
    return 3;
  }
  return 1;
}
