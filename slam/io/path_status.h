// A path's type, read so that a filesystem failure becomes duskmap's one-line
// InputError instead of std::filesystem's exception text: the dataset readers
// call this wherever they ask whether a file or folder exists.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace duskmap {

// The status of `path` (following symlinks); a missing path gives
// file_type::not_found. Any other failure (a symlink loop, no permission)
// throws InputError "<path>: <problem>".
std::filesystem::file_status PathStatus(const std::filesystem::path& path);

bool PathExists(const std::filesystem::path& path);       // anything, following symlinks
bool IsDirectoryPath(const std::filesystem::path& path);  // a folder, following symlinks

// The entries of a folder, sorted by path; a folder that cannot be listed
// throws InputError "<folder>: <problem>".
std::vector<std::filesystem::path> SortedFolderEntries(const std::filesystem::path& folder);

}  // namespace duskmap
