// The two small types that output safety (io/output_safety.h) and publishing
// (io/publish.h) share: a path with the flag that named it, and what
// --overwrite may replace at a path. Their own header so that publishing
// does not depend on output safety, which writes files through it.
#pragma once

#include <filesystem>
#include <functional>
#include <string>

namespace duskmap {

// A path a command reads or writes, with the flag (or config key) that named
// it, for the error messages.
struct NamedPath {
  std::string flag;  // "--dataset", "--map", "config", ...
  std::string path;
};

// What --overwrite may replace: a description for messages ("a duskmap map")
// and the test that recognises it.
struct OwnedOutput {
  std::string what;    // "a duskmap dataset (manifest.json)"
  std::function<bool(const std::filesystem::path&)> is_owned;
};

}  // namespace duskmap
