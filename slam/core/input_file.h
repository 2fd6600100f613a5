// The one check every user-named input file passes before it is opened: a
// FIFO opened for reading blocks until a writer appears (a `--map` FIFO hung
// the program), a device can be endless, and a folder opens but reads as
// nothing. Such a path is refused by its type, from stat(), without opening it.
#pragma once

#include <string>

namespace duskmap {

// Throws InputError "<path>: is a FIFO (named pipe), not a regular file" (or
// "a folder", "a socket", "a character device", "a block device") when `path`,
// symlinks followed, exists and is not a regular file; with `flag` the message
// starts "<flag> <path>: ...". A missing path is not judged here: the reader
// that opens it names it in its own words ("no such map file", "ONNX model not
// found"). Any other stat() failure (no permission on a folder on the way, a
// symlink loop) throws "<path>: <system's reason>".
void RefuseNonRegularFile(const std::string& path, const std::string& flag = "");

}  // namespace duskmap
