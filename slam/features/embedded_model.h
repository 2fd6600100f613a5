// The ONNX model compiled into the library: the dusknet type's
// slam/features/models/dusknet.onnx, embedded at build time
// (slam/features/models/embed_model.cmake), so that the type works from any
// directory. Its checksum keys the feature caches (experiment/feature_files.h)
// as a model file's would.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace duskmap {

struct EmbeddedModel {
  const char* bytes = nullptr;
  size_t size = 0;
  uint64_t checksum = 0;  // BytesChecksum64: a file of these bytes has FileChecksum64 the same
  std::string checksum_hex;  // the same as 16 lowercase hexadecimal digits
  std::string name;       // "embedded:dusknet.onnx": how errors and records name it
};

const EmbeddedModel& EmbeddedDuskNetModel();

}  // namespace duskmap
