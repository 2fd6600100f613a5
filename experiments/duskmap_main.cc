// The `duskmap` command-line program: one binary, one subcommand per job.
#include <malloc.h>
#include <stdlib.h>

#include <cstdlib>
#include <exception>
#include <iostream>
#include <map>
#include <string>

#include "experiments/command_registry.h"
#include "slam/core/check.h"
#include "slam/io/publish.h"

namespace {

// Keeps freed heap memory in the process instead of handing it back to the
// kernel as soon as a frame's buffers are freed. OpenCV's detectors allocate
// and free megabytes of image pyramids per frame; with glibc's defaults
// their pages were unmapped and faulted in again frame after frame: one KAZE
// extraction job of a 160-frame session took 119 s on a 2-core VM, 53 s with
// these settings, with the same results (docs/experiments.md, "Jobs, caches,
// resume, shards").
void KeepFreedHeapMemory() {
  mallopt(M_MMAP_THRESHOLD, 32 << 20);  // heap, not mmap, up to 32 MiB (glibc's largest)
  mallopt(M_TRIM_THRESHOLD, 1 << 30);   // trim only above 1 GiB of free top
  mallopt(M_TOP_PAD, 256 << 20);        // grow the heap 256 MiB at a time
}

// Test-only (tests/cli): DUSKMAP_TEST_BEFORE_PUBLISH holds a shell command
// run right before each output is given its final name, with
// DUSKMAP_PUBLISH_PATH set to that name, so that a test can make a file
// appear there mid-run. The variable is removed first: the commands it runs
// (another duskmap) do not run it again. Its exit status is ignored.
void InstallTestPublishHook() {
  const char* command = std::getenv("DUSKMAP_TEST_BEFORE_PUBLISH");
  if (command == nullptr || *command == '\0') return;
  const std::string text = command;
  ::unsetenv("DUSKMAP_TEST_BEFORE_PUBLISH");
  duskmap::SetBeforePublishHookForTesting([text](const std::string& path) {
    std::string quoted = "'";
    for (const char c : path) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
    quoted += "'";
    const std::string script = "DUSKMAP_PUBLISH_PATH=" + quoted +
                               "; export DUSKMAP_PUBLISH_PATH; " + text;
    [[maybe_unused]] const int status = std::system(script.c_str());
  });
}

}  // namespace

int main(int argc, char** argv) {
  KeepFreedHeapMemory();
  InstallTestPublishHook();
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
