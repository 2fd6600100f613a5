#include "slam/io/publish.h"

#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <sstream>
#include <system_error>
#include <utility>
#include <vector>

#include "slam/core/check.h"

#ifndef RENAME_NOREPLACE
#define RENAME_NOREPLACE (1 << 0)
#endif

namespace duskmap {
namespace fs = std::filesystem;
namespace {

std::mutex& HookMutex() {
  static std::mutex mutex;
  return mutex;
}

BeforePublishHook& Hook() {
  static BeforePublishHook hook;
  return hook;
}

void RunHook(const std::string& final_path) {
  BeforePublishHook hook;
  {
    const std::lock_guard<std::mutex> lock(HookMutex());
    hook = Hook();
  }
  if (hook) hook(final_path);
}

// The folder that holds `path` ("." for a bare name).
std::string ParentOf(const std::string& path) {
  const fs::path parent = fs::path(path).parent_path();
  return parent.empty() ? std::string(".") : parent.string();
}

// Flushes a file (or a folder's entries) to disk; returns errno or 0.
int Flush(const std::string& path, bool directory) {
  const int fd = ::open(path.c_str(), (directory ? O_RDONLY | O_DIRECTORY : O_RDONLY) | O_CLOEXEC);
  if (fd < 0) return errno;
  const int failure = ::fsync(fd) == 0 ? 0 : errno;
  ::close(fd);
  return failure;
}

// Gives `from` the name `to` unless `to` exists; returns 0 or errno (EEXIST
// when the name is taken). renameat2(RENAME_NOREPLACE) where the filesystem
// supports it; else link(2) + unlink for a file, and for a folder an empty
// folder created at `to` as a claim (mkdir fails when the name exists) that
// the rename then replaces.
int RenameNoReplace(const std::string& from, const std::string& to) {
  if (::renameat2(AT_FDCWD, from.c_str(), AT_FDCWD, to.c_str(), RENAME_NOREPLACE) == 0) return 0;
  const int reason = errno;
  if (reason != EINVAL && reason != ENOSYS && reason != EOPNOTSUPP) return reason;
  struct stat info;
  if (::lstat(from.c_str(), &info) != 0) return errno;
  if (S_ISDIR(info.st_mode)) {
    if (::mkdir(to.c_str(), 0755) != 0) return errno;
    if (::rename(from.c_str(), to.c_str()) != 0) {
      const int failure = errno;
      ::rmdir(to.c_str());
      return failure;
    }
    return 0;
  }
  if (::link(from.c_str(), to.c_str()) != 0) return errno;
  ::unlink(from.c_str());
  return 0;
}

bool Exists(const std::string& path) {
  std::error_code error;
  return fs::exists(fs::symlink_status(path, error));
}

void ThrowAppeared(const PublishTarget& target) {
  SLAM_THROW(InputError) << target.output.path << ": appeared while this command ran ("
                         << target.output.flag
                         << "); nothing was replaced (pass --overwrite to replace it)";
}

void ThrowNotOwned(const PublishTarget& target) {
  SLAM_THROW(InputError) << target.output.path << ": not " << target.owner.what
                         << ", so --overwrite will not replace it; choose another path";
}

bool IsOwned(const PublishTarget& target, const std::string& path) {
  return !target.owner.is_owned || target.owner.is_owned(path);
}

// Parses "<pid>" or "<pid>-<n>"; 0 when `text` is neither.
pid_t PidOfSuffix(const std::string& text) {
  size_t digits = 0;
  while (digits < text.size() && std::isdigit(static_cast<unsigned char>(text[digits]))) ++digits;
  if (digits == 0 || digits > 9) return 0;
  if (digits < text.size()) {
    if (text[digits] != '-' || digits + 1 == text.size()) return 0;
    for (size_t i = digits + 1; i < text.size(); ++i) {
      if (!std::isdigit(static_cast<unsigned char>(text[i]))) return 0;
    }
  }
  return static_cast<pid_t>(std::stol(text.substr(0, digits)));
}

}  // namespace

PublishTarget ReplaceAnyFile(const std::string& path) {
  return {{"output", path}, /*overwrite=*/true, {"a file", nullptr}};
}

std::string TemporarySiblingOf(const std::string& path, const std::string& tag) {
  static std::atomic<uint64_t> counter{0};
  return path + "." + tag + "-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
}

namespace {

// Calls `visit` with each sibling of `path` named "<name>.<tag>-<pid>[-<n>]"
// whose process is no longer running.
template <typename Visit>
void ForEachStaleSibling(const std::string& path, const std::string& tag, Visit visit) {
  fs::path normal = fs::path(path).lexically_normal();
  if (!normal.has_filename() && normal.has_parent_path()) normal = normal.parent_path();
  const std::string prefix = normal.filename().string() + "." + tag + "-";
  fs::path folder = normal.parent_path();
  if (folder.empty()) folder = ".";
  std::vector<fs::path> stale;
  std::error_code error;
  for (fs::directory_iterator it(folder, error), end; !error && it != end; it.increment(error)) {
    const std::string name = it->path().filename().string();
    if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0) continue;
    const pid_t pid = PidOfSuffix(name.substr(prefix.size()));
    if (pid <= 0 || pid == ::getpid()) continue;
    if (::kill(pid, 0) == 0 || errno != ESRCH) continue;  // running (or not ours to signal)
    stale.push_back(it->path());
  }
  for (const fs::path& sibling : stale) visit(sibling);
}

}  // namespace

int RemoveStaleSiblings(const std::string& path, const std::string& tag) {
  int removed = 0;
  ForEachStaleSibling(path, tag, [&](const fs::path& sibling) {
    std::error_code error;
    if (fs::remove_all(sibling, error) > 0 && !error) ++removed;
  });
  return removed;
}

void RecoverStaleAside(const std::string& path) {
  ForEachStaleSibling(path, "old", [&](const fs::path& sibling) {
    if (!Exists(path) && RenameNoReplace(sibling.string(), path) == 0) return;
    std::error_code error;
    fs::remove_all(sibling, error);
  });
}

void PublishFile(const std::string& temp_path, const PublishTarget& target) {
  const std::string& path = target.output.path;
  const auto fail = [&](int reason) {
    std::remove(temp_path.c_str());
    SLAM_THROW(InputError) << path << ": cannot write: " << std::strerror(reason)
                           << " (nothing was changed)";
  };
  if (const int failure = Flush(temp_path, /*directory=*/false)) fail(failure);
  RunHook(path);
  int failure = RenameNoReplace(temp_path, path);
  if (failure == EEXIST) {
    if (!target.overwrite) {
      std::remove(temp_path.c_str());
      ThrowAppeared(target);
    }
    // Checked right before the replace: what is there now is what goes.
    if (!IsOwned(target, path)) {
      std::remove(temp_path.c_str());
      ThrowNotOwned(target);
    }
    failure = std::rename(temp_path.c_str(), path.c_str()) == 0 ? 0 : errno;
  }
  if (failure != 0) fail(failure);
  Flush(ParentOf(path), /*directory=*/true);  // the new name on disk (best effort)
}

void PublishFolder(const std::string& staging_path, const PublishTarget& target) {
  const std::string& path = target.output.path;
  RunHook(path);
  int failure = RenameNoReplace(staging_path, path);
  if (failure == 0) {
    Flush(ParentOf(path), /*directory=*/true);
    return;
  }
  if (failure != EEXIST && failure != ENOTEMPTY) {
    SLAM_THROW(InputError) << path << ": cannot rename " << staging_path << " into place ("
                           << std::strerror(failure) << "); nothing was replaced";
  }
  if (!target.overwrite) ThrowAppeared(target);
  // Moved aside first, so that the folder tested is the folder replaced.
  const std::string aside = TemporarySiblingOf(path, "old");
  SLAM_THROW_IF_NOT(InputError, std::rename(path.c_str(), aside.c_str()) == 0)
      << path << ": cannot move the old folder aside (" << std::strerror(errno)
      << "); nothing was replaced";
  const auto put_back = [&]() -> std::string {
    const int back = RenameNoReplace(aside, path);
    return back == 0 ? std::string("left as it was")
                     : "moved to " + aside + " (" + std::strerror(back) + ")";
  };
  if (!IsOwned(target, aside)) {
    const std::string where = put_back();
    SLAM_THROW(InputError) << path << ": not " << target.owner.what
                           << ", so --overwrite will not replace it (" << where
                           << "); choose another path";
  }
  failure = RenameNoReplace(staging_path, path);
  if (failure != 0) {
    const std::string where = put_back();
    if (failure == EEXIST || failure == ENOTEMPTY) {
      SLAM_THROW(InputError) << path << ": appeared while this command ran (" << target.output.flag
                             << "); nothing was replaced (the old folder is " << where << ")";
    }
    SLAM_THROW(InputError) << path << ": cannot rename " << staging_path << " into place ("
                           << std::strerror(failure) << "); the old folder is " << where;
  }
  Flush(ParentOf(path), /*directory=*/true);
  std::error_code error;
  fs::remove_all(aside, error);
}

void WriteAndPublishAt(const PublishTarget& target,
                       const std::function<void(const std::string& temp_path)>& write) {
  const std::string& path = target.output.path;
  RemoveStaleSiblings(path, "partial");
  const std::string temp = TemporarySiblingOf(path, "partial");
  try {
    write(temp);
  } catch (...) {
    std::remove(temp.c_str());
    throw;
  }
  PublishFile(temp, target);
}

void WriteAndPublish(const PublishTarget& target, const std::function<void(std::ostream&)>& write) {
  const std::string& path = target.output.path;
  std::ostringstream buffer;
  write(buffer);
  SLAM_THROW_IF_NOT(InputError, buffer.good()) << path << ": cannot format the output";
  const std::string bytes = buffer.str();
  WriteAndPublishAt(target, [&](const std::string& temp) {
    const int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
    SLAM_THROW_IF_NOT(InputError, fd >= 0) << path << ": cannot write: " << std::strerror(errno);
    int failure = 0;
    for (size_t done = 0; done < bytes.size() && failure == 0;) {
      const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) {
        failure = n < 0 ? errno : EIO;
      } else {
        done += static_cast<size_t>(n);
      }
    }
    if (::close(fd) != 0 && failure == 0) failure = errno;
    SLAM_THROW_IF_NOT(InputError, failure == 0)
        << path << ": cannot write: " << std::strerror(failure) << " (nothing was changed)";
  });
}

void SetBeforePublishHookForTesting(BeforePublishHook hook) {
  const std::lock_guard<std::mutex> lock(HookMutex());
  Hook() = std::move(hook);
}

}  // namespace duskmap
