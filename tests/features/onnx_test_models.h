// Test ONNX models, written into the build directory by the project's
// scripts (Debian python3-onnx): each returns the model path, or "" when the
// script cannot run (the caller skips). A model is rewritten when its script
// is newer; files are written under a temporary name and renamed, so test
// processes running in parallel never read half a model.
#pragma once

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>

namespace duskmap::testing {

inline bool UpToDate(const std::filesystem::path& output, const std::filesystem::path& script) {
  std::error_code ec;
  if (!std::filesystem::exists(output, ec)) return false;
  return std::filesystem::last_write_time(output, ec) >= std::filesystem::last_write_time(script, ec);
}

// Runs scripts/<script> OUT [flags] [--test-vector DIR]; empty on failure.
inline std::string RunModelScript(const std::string& script, const std::string& file,
                                  const std::string& flags, const std::string& test_vector_dir) {
  namespace fs = std::filesystem;
  const fs::path source = fs::path(DUSKMAP_SOURCE_DIR) / "scripts" / script;
  const fs::path path = fs::path(DUSKMAP_BINARY_DIR) / file;
  const bool need_vector = !test_vector_dir.empty();
  if (UpToDate(path, source) && (!need_vector || UpToDate(fs::path(test_vector_dir) / "index.txt", source))) {
    return path.string();
  }
  const std::string tag = ".tmp." + std::to_string(::getpid());
  const std::string python = fs::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
  std::string command = python + " " + source.string() + " " + path.string() + tag + " " + flags;
  if (need_vector) command += " --test-vector " + test_vector_dir + tag;
  command += " > /dev/null 2>&1";
  std::error_code ec;
  if (std::system(command.c_str()) != 0 || !fs::exists(path.string() + tag)) {
    fs::remove(path.string() + tag, ec);
    fs::remove_all(test_vector_dir + tag, ec);
    return "";
  }
  if (need_vector) {
    fs::remove_all(test_vector_dir, ec);
    fs::rename(test_vector_dir + tag, test_vector_dir, ec);
    fs::remove_all(test_vector_dir + tag, ec);  // another process renamed first
  }
  fs::rename(path.string() + tag, path, ec);
  return fs::exists(path) ? path.string() : "";
}

// SuperPoint's architecture with random weights (make_test_superpoint_onnx.py).
inline std::string MakeSuperPointModel(const std::string& file, const std::string& flags = "") {
  return RunModelScript("make_test_superpoint_onnx.py", file, flags, "");
}

// A small dense or sparse local-feature model (make_test_onnx_features.py);
// `flags` such as "--contract sparse --rgb".
inline std::string MakeOnnxFeatureModel(const std::string& file, const std::string& flags) {
  return RunModelScript("make_test_onnx_features.py", file, flags, "");
}

// A linear patch descriptor (make_test_onnx_patch.py) written to `path`, not
// cached (each caller names its own path); `flags` such as "--dims 16
// --weights W.f32". False when the script cannot run (the caller skips).
inline bool MakeOnnxPatchModel(const std::string& path, const std::string& flags) {
  namespace fs = std::filesystem;
  const fs::path script = fs::path(DUSKMAP_SOURCE_DIR) / "scripts" / "make_test_onnx_patch.py";
  const std::string python = fs::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
  const std::string command =
      python + " " + script.string() + " " + path + " " + flags + " > /dev/null 2>&1";
  std::error_code ec;
  return std::system(command.c_str()) == 0 && fs::exists(path, ec);
}

}  // namespace duskmap::testing
