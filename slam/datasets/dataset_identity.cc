#include "slam/datasets/dataset_identity.h"

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <map>
#include <system_error>

#include "slam/core/check.h"
#include "slam/core/checksum.h"
#include "slam/core/file_checksum.h"
#include "slam/io/synthetic_dataset.h"

namespace duskmap {
namespace fs = std::filesystem;
namespace {

// Every regular file of the dataset as (relative path, full path), sorted by
// relative path so that no checksum depends on the directory's listing order.
std::vector<std::pair<std::string, fs::path>> ListFiles(const std::string& path) {
  std::error_code error;
  std::vector<std::pair<std::string, fs::path>> files;
  if (!fs::is_directory(path, error)) {
    files.push_back({fs::path(path).filename().string(), fs::path(path)});
    return files;
  }
  fs::recursive_directory_iterator it(path, fs::directory_options::skip_permission_denied, error);
  SLAM_THROW_IF_NOT(InputError, !error) << path << ": cannot list the dataset (" << error.message() << ")";
  for (; it != fs::recursive_directory_iterator(); it.increment(error)) {
    SLAM_THROW_IF_NOT(InputError, !error)
        << path << ": cannot list the dataset (" << error.message() << ")";
    if (it->is_regular_file(error)) {
      files.push_back({fs::relative(it->path(), path, error).generic_string(), it->path()});
    }
  }
  std::sort(files.begin(), files.end());
  return files;
}

// The top-level folder (or file) of each session, by session name.
std::map<std::string, std::string> SessionRoots(const std::string& path, const std::string& format,
                                                const std::vector<SessionInfo>& sessions) {
  std::map<std::string, std::string> roots;
  for (const SessionInfo& s : sessions) roots[s.name] = s.name;
  std::error_code error;
  const bool synthetic = format == "synthetic" ||
                         (format == "auto" && fs::is_regular_file(fs::path(path) / kManifestFileName, error));
  if (synthetic) {
    for (const ManifestSession& s : ReadManifest(path).sessions) {
      if (roots.count(s.name)) roots[s.name] = fs::path(s.folder).lexically_normal().generic_string();
    }
  }
  return roots;
}

// The session that owns the file at `relative`, or "" for a shared file.
std::string OwnerOf(const std::string& relative, const std::map<std::string, std::string>& roots,
                    size_t num_sessions) {
  if (num_sessions == 1) return roots.begin()->first;
  for (const auto& [name, root] : roots) {
    if (relative.size() > root.size() && relative.compare(0, root.size(), root) == 0 &&
        relative[root.size()] == '/') {
      return name;
    }
  }
  const fs::path file(relative);
  if (!file.has_parent_path()) {  // a top-level file: "<name>.db"
    const auto it = roots.find(file.stem().string());
    if (it != roots.end() && it->second == it->first) return it->first;
  }
  return "";
}

// Accumulates (relative path, content checksum) records of one owner.
void AddRecord(const std::string& relative, uint64_t checksum, std::string* records) {
  records->append(relative);
  records->push_back('\0');
  records->append(reinterpret_cast<const char*>(&checksum), sizeof(checksum));
}

}  // namespace

nlohmann::json DatasetIdentity(const std::string& path, const std::string& format,
                               const std::vector<SessionInfo>& sessions) {
  nlohmann::json identity;
  identity["format"] = format;
  nlohmann::json listed = nlohmann::json::array();
  for (const SessionInfo& s : sessions) {
    listed.push_back({{"name", s.name},
                      {"frames", s.num_frames},
                      {"clock_time", s.clock_time ? *s.clock_time : std::string()}});
  }
  identity["sessions"] = listed;

  const std::vector<std::pair<std::string, fs::path>> files = ListFiles(path);
  const std::map<std::string, std::string> roots = SessionRoots(path, format, sessions);
  std::map<std::string, std::string> records;  // owner ("" = shared) -> its records
  for (const SessionInfo& s : sessions) records[s.name];
  records[""];
  uintmax_t total_bytes = 0;
  std::error_code error;
  for (const auto& [relative, full] : files) {
    const uintmax_t bytes = fs::file_size(full, error);
    SLAM_THROW_IF_NOT(InputError, !error) << full.string() << ": cannot stat (" << error.message() << ")";
    total_bytes += bytes;
    const std::string owner = roots.empty() ? "" : OwnerOf(relative, roots, sessions.size());
    AddRecord(relative, FileChecksum64(full), &records[owner]);
  }
  nlohmann::json content;
  content["sessions"] = nlohmann::json::object();
  for (const auto& [owner, text] : records) {
    const std::string checksum = Checksum64Hex(text.data(), text.size());
    if (owner.empty()) {
      content["shared"] = checksum;
    } else {
      content["sessions"][owner] = checksum;
    }
  }
  identity["files"] = files.size();
  identity["bytes"] = total_bytes;
  identity["content"] = content;
  return identity;
}

nlohmann::json SessionIdentity(const nlohmann::json& dataset_identity, const std::string& session) {
  nlohmann::json identity = dataset_identity;
  if (!identity.is_object()) return identity;
  if (identity.contains("sessions") && identity["sessions"].is_array()) {
    nlohmann::json own;
    for (const nlohmann::json& listed : identity["sessions"]) {
      if (listed.is_object() && listed.value("name", std::string()) == session) own = listed;
    }
    identity.erase("sessions");
    identity["session"] = own;
  }
  identity.erase("files");
  identity.erase("bytes");
  if (identity.contains("content") && identity["content"].is_object() &&
      identity["content"].contains("sessions")) {
    const nlohmann::json& by_session = identity["content"]["sessions"];
    nlohmann::json own = by_session.is_object() && by_session.contains(session) ? by_session[session]
                                                                               : nlohmann::json();
    identity["content"].erase("sessions");
    identity["content"]["session"] = own;
  }
  return identity;
}

}  // namespace duskmap
