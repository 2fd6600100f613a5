// Where a mesh's files come from: a reader of files by archive path
// (archive_path.h), so that the OBJ/MTL loader works alike on a furniture
// catalog's ZIP and on text a test holds in memory.
#pragma once

#include <functional>
#include <optional>
#include <string>

namespace duskmap {

struct MeshFiles {
  // Names the container in messages: "<container>!/<path>"; empty = the
  // paths alone.
  std::string container;
  // The bytes of the file at an archive path, or nullopt when there is no
  // such file; may throw InputError for a file that exists but cannot be read.
  std::function<std::optional<std::string>(const std::string& path)> read;

  // How messages name a file: "<container>!/<path>", or the path.
  std::string Describe(const std::string& path) const {
    return container.empty() ? path : container + "!/" + path;
  }
};

}  // namespace duskmap
