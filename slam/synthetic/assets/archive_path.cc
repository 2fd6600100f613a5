#include "slam/synthetic/assets/archive_path.h"

#include <algorithm>
#include <cctype>
#include <vector>

namespace duskmap {
namespace {

// "C:", "C:foo" (a Windows drive) or "scheme:" as the first component.
bool HasDriveOrScheme(const std::string& first_component) {
  if (first_component.size() >= 2 && std::isalpha(static_cast<unsigned char>(first_component[0])) &&
      first_component[1] == ':') {
    return true;
  }
  return !first_component.empty() && first_component.back() == ':';
}

}  // namespace

std::optional<std::string> NormalizeArchivePath(const std::string& path) {
  std::string slashed = path;
  std::replace(slashed.begin(), slashed.end(), '\\', '/');
  if (slashed.empty() || slashed.front() == '/') return std::nullopt;
  std::vector<std::string> parts;
  size_t begin = 0;
  while (begin <= slashed.size()) {
    const size_t end = std::min(slashed.find('/', begin), slashed.size());
    const std::string part = slashed.substr(begin, end - begin);
    if (begin == 0 && HasDriveOrScheme(part)) return std::nullopt;
    if (part == "..") {
      if (parts.empty()) return std::nullopt;
      parts.pop_back();
    } else if (!part.empty() && part != ".") {
      parts.push_back(part);
    }
    begin = end + 1;
  }
  if (parts.empty()) return std::nullopt;
  std::string normalized = parts.front();
  for (size_t i = 1; i < parts.size(); ++i) normalized += "/" + parts[i];
  return normalized;
}

std::string ArchiveFolder(const std::string& path) {
  const size_t slash = path.rfind('/');
  return slash == std::string::npos ? std::string() : path.substr(0, slash + 1);
}

std::optional<std::string> ResolveArchiveReference(const std::string& folder, const std::string& reference) {
  std::string slashed = reference;
  std::replace(slashed.begin(), slashed.end(), '\\', '/');
  const std::string first = slashed.substr(0, slashed.find('/'));
  if (slashed.empty() || slashed.front() == '/' || HasDriveOrScheme(first)) return std::nullopt;
  return NormalizeArchivePath(folder + slashed);
}

}  // namespace duskmap
