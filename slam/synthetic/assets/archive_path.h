// Paths of the files inside an archive (a furniture catalog's ZIP):
// '/'-separated, relative to the archive root, with no "." or ".." component.
// The catalog reads only such paths, and the OBJ/MTL loader resolves every
// file name a model gives against the folder of the file that names it, so
// that no reference reaches outside the archive.
#pragma once

#include <optional>
#include <string>

namespace duskmap {

// `path` as an archive path: '\' read as '/', empty and "." components
// dropped, ".." removing the component before it. nullopt when the path is
// empty, absolute (a leading '/' or '\', a drive such as "C:" or a URL scheme
// such as "file:") or climbs above the archive root.
std::optional<std::string> NormalizeArchivePath(const std::string& path);

// The folder of an archive path with its trailing '/', or "" for a file at
// the root: "a/b/c.obj" -> "a/b/".
std::string ArchiveFolder(const std::string& path);

// `reference` (a file name as an OBJ or MTL file gives it) resolved against
// `folder` (ArchiveFolder of the naming file); nullopt when the reference is
// absolute or the result leaves the archive.
std::optional<std::string> ResolveArchiveReference(const std::string& folder, const std::string& reference);

}  // namespace duskmap
