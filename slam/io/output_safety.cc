#include "slam/io/output_safety.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <system_error>

#include <nlohmann/json.hpp>

#include "slam/core/check.h"
#include "slam/core/json_reader.h"
#include "slam/io/publish.h"
#include "slam/io/synthetic_marker.h"

namespace duskmap {
namespace fs = std::filesystem;
namespace {

// The absolute form with symbolic links and ".." resolved as far as the
// path exists; the rest is normalised lexically.
fs::path Resolved(const fs::path& path) {
  std::error_code error;
  fs::path absolute = fs::absolute(path, error);
  if (error) absolute = path;
  fs::path resolved = fs::weakly_canonical(absolute, error);
  if (error) resolved = absolute.lexically_normal();
  // "a/b/" and "a/b" are the same folder.
  if (!resolved.has_filename() && resolved.has_parent_path()) resolved = resolved.parent_path();
  return resolved;
}

}  // namespace

bool IsSameOrInside(const fs::path& path, const fs::path& folder) {
  const fs::path p = Resolved(path);
  const fs::path f = Resolved(folder);
  auto pi = p.begin();
  for (auto fi = f.begin(); fi != f.end(); ++fi, ++pi) {
    if (pi == p.end() || *pi != *fi) return false;
  }
  return true;
}

void CheckOutputsApartFromInputs(const std::vector<NamedPath>& outputs,
                                 const std::vector<NamedPath>& inputs) {
  for (size_t i = 0; i < outputs.size(); ++i) {
    const NamedPath& out = outputs[i];
    if (out.path.empty()) continue;
    for (const NamedPath& in : inputs) {
      if (in.path.empty()) continue;
      SLAM_THROW_IF_NOT(InputError, !IsSameOrInside(out.path, in.path))
          << out.path << ": " << out.flag << " would write "
          << (Resolved(out.path) == Resolved(in.path) ? "onto" : "inside") << " the input "
          << in.path << " (" << in.flag << "); choose another path";
    }
    for (size_t j = 0; j < i; ++j) {
      if (outputs[j].path.empty()) continue;
      SLAM_THROW_IF_NOT(InputError, Resolved(outputs[j].path) != Resolved(out.path))
          << out.path << ": given to both " << outputs[j].flag << " and " << out.flag;
    }
  }
}

void CheckMayReplace(const NamedPath& output, bool overwrite, const OwnedOutput& owner) {
  std::error_code error;
  const fs::file_status status = fs::symlink_status(output.path, error);
  if (!fs::exists(status)) return;
  SLAM_THROW_IF_NOT(InputError, overwrite)
      << output.path << ": already exists (" << output.flag
      << "; pass --overwrite to replace it)";
  SLAM_THROW_IF_NOT(InputError, owner.is_owned(output.path))
      << output.path << ": not " << owner.what
      << ", so --overwrite will not replace it; choose another path";
}

bool IsDuskmapDatasetFolder(const fs::path& path) {
  std::error_code error;
  if (!fs::is_directory(path, error)) return false;
  // Only the format field: a damaged manifest of a generated dataset is
  // still the generator's to replace.
  nlohmann::json json;
  try {
    json = ReadJsonFile((path / kManifestFileName).string());
  } catch (const Error&) {  // missing, not JSON, or nested too deep
    return false;
  }
  return json.is_object() && json.contains("format") && json.at("format") == kSyntheticFormat;
}

bool IsDuskmapResultsFolder(const fs::path& path) {
  std::error_code error;
  return fs::is_directory(path, error) && fs::is_regular_file(path / "run.json", error);
}

OwnedOutput OwnedDataset() {
  return {"a duskmap dataset (no manifest.json of format duskmap-synthetic)",
          &IsDuskmapDatasetFolder};
}

OwnedOutput OwnedResultsFolder() {
  return {"a duskmap results folder (no run.json)", &IsDuskmapResultsFolder};
}

void CheckPathLabel(const std::string& label, const std::string& where) {
  SLAM_THROW_IF_NOT(ConfigError, !label.empty()) << where << ": empty label";
  bool clean = label.size() <= kMaxPathLabelBytes && label != "." && label != ".." && label[0] != '.';
  for (const char c : label) {
    if (c == '/' || c == '\\' || static_cast<unsigned char>(c) < 0x20 || c == 0x7f) clean = false;
  }
  SLAM_THROW_IF_NOT(ConfigError, clean)
      << where << ": '" << label
      << "' cannot name a results folder (no '/', '\\', control characters or leading '.', "
         "at most " << kMaxPathLabelBytes << " bytes)";
}

FolderLock::FolderLock(const fs::path& folder) {
  const fs::path path = folder / kFileName;
  fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  SLAM_THROW_IF_NOT(InputError, fd_ >= 0)
      << path.string() << ": cannot create the lock file: " << std::strerror(errno);
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    const int reason = errno;
    char holder[32] = {};
    const ssize_t n = ::pread(fd_, holder, sizeof(holder) - 1, 0);
    ::close(fd_);
    fd_ = -1;
    SLAM_THROW_IF_NOT(InputError, reason != EWOULDBLOCK)
        << folder.string() << ": another duskmap process"
        << (n > 0 ? " (pid " + std::string(holder, static_cast<size_t>(n)) + ")" : std::string())
        << " is writing this folder; wait for it or choose another folder";
    SLAM_THROW(InputError) << path.string() << ": cannot lock: " << std::strerror(reason);
  }
  const std::string pid = std::to_string(::getpid());
  if (::ftruncate(fd_, 0) == 0) {
    [[maybe_unused]] const ssize_t written = ::pwrite(fd_, pid.data(), pid.size(), 0);
  }
}

FolderLock::~FolderLock() {
  if (fd_ >= 0) ::close(fd_);  // releases the lock
}

void WriteFileAtomicallyAt(const std::string& path,
                           const std::function<void(const std::string& partial_path)>& write) {
  WriteAndPublishAt(ReplaceAnyFile(path), write);
}

void WriteFileAtomically(const std::string& path, const std::function<void(std::ostream&)>& write) {
  WriteAndPublish(ReplaceAnyFile(path), write);
}

}  // namespace duskmap
