#include "slam/features/embedded_model.h"

#include <cstdio>

#include "slam/core/file_checksum.h"

namespace duskmap {

// Defined in the generated embedded_dusknet_model.cc (slam/features/CMakeLists.txt).
extern const char kDuskNetOnnx[];
extern const size_t kDuskNetOnnx_bytes;

const EmbeddedModel& EmbeddedDuskNetModel() {
  static const EmbeddedModel kModel = [] {
    EmbeddedModel model;
    model.bytes = kDuskNetOnnx;
    model.size = kDuskNetOnnx_bytes;
    model.checksum = BytesChecksum64(model.bytes, model.size);
    char hex[17];
    std::snprintf(hex, sizeof(hex), "%016llx", static_cast<unsigned long long>(model.checksum));
    model.checksum_hex = hex;
    model.name = "embedded:dusknet.onnx";
    return model;
  }();
  return kModel;
}

}  // namespace duskmap
