// The declared shape of an ONNX model's first input, read from the model's
// bytes (the ModelProto wire format: graph.input's tensor type and shape).
// OpenCV 4.6's DNN does not expose it, and a fully convolutional model with
// global pooling runs on any patch size, so only the declaration tells that
// a patch model was made for another size (onnx_patch_extractor.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace duskmap {

struct OnnxDeclaredInput {
  std::string name;
  bool has_shape = false;  // false: the input declares no shape at all
  // One entry per dimension: its fixed size, or -1 when symbolic ("N") or unset.
  std::vector<int64_t> dims;
  // "Nx1x64x64": symbolic and unset dimensions as "?"; "unknown" without a shape.
  std::string ToString() const;
};

// The first graph input that is not an initializer (older exporters list
// weights as inputs too); nullopt when the bytes are not a well-formed
// ModelProto with a graph input.
std::optional<OnnxDeclaredInput> ReadOnnxDeclaredInput(const char* bytes, size_t size);

}  // namespace duskmap
