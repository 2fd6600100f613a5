#include "slam/features/onnx_declared_input.h"

#include <algorithm>
#include <string_view>

namespace duskmap {
namespace {

// Field numbers of onnx.proto (ONNX's public schema).
constexpr uint32_t kModelGraph = 7;            // ModelProto.graph
constexpr uint32_t kGraphInitializer = 5;      // GraphProto.initializer
constexpr uint32_t kGraphInput = 11;           // GraphProto.input
constexpr uint32_t kTensorName = 8;            // TensorProto.name
constexpr uint32_t kValueInfoName = 1;         // ValueInfoProto.name
constexpr uint32_t kValueInfoType = 2;         // ValueInfoProto.type
constexpr uint32_t kTypeTensor = 1;            // TypeProto.tensor_type
constexpr uint32_t kTensorTypeShape = 2;       // TypeProto.Tensor.shape
constexpr uint32_t kShapeDim = 1;              // TensorShapeProto.dim
constexpr uint32_t kDimValue = 1;              // TensorShapeProto.Dimension.dim_value

constexpr uint32_t kWireVarint = 0, kWireFixed64 = 1, kWireBytes = 2, kWireFixed32 = 5;

// One protobuf message's fields, in order; any malformed byte stops it with ok() false.
class WireReader {
 public:
  explicit WireReader(std::string_view bytes) : rest_(bytes) {}
  bool ok() const { return ok_; }

  // The next field; false at the end or on an error.
  bool Next(uint32_t* field, uint32_t* wire, uint64_t* varint, std::string_view* bytes) {
    if (!ok_ || rest_.empty()) return false;
    uint64_t key = 0;
    if (!Varint(&key) || (key >> 3) == 0) return Fail();
    *field = static_cast<uint32_t>(key >> 3);
    *wire = static_cast<uint32_t>(key & 7);
    switch (*wire) {
      case kWireVarint:
        return Varint(varint) || Fail();
      case kWireFixed64:
        return Skip(8);
      case kWireFixed32:
        return Skip(4);
      case kWireBytes: {
        uint64_t length = 0;
        if (!Varint(&length) || length > rest_.size()) return Fail();
        *bytes = rest_.substr(0, static_cast<size_t>(length));
        rest_.remove_prefix(static_cast<size_t>(length));
        return true;
      }
      default:
        return Fail();  // groups (3, 4) are not used by onnx.proto
    }
  }

 private:
  bool Varint(uint64_t* value) {
    *value = 0;
    for (int shift = 0; shift < 64 && !rest_.empty(); shift += 7) {
      const auto byte = static_cast<uint8_t>(rest_.front());
      rest_.remove_prefix(1);
      *value |= static_cast<uint64_t>(byte & 0x7f) << shift;
      if ((byte & 0x80) == 0) return true;
    }
    return false;
  }
  bool Skip(size_t n) {
    if (n > rest_.size()) return Fail();
    rest_.remove_prefix(n);
    return true;
  }
  bool Fail() {
    ok_ = false;
    return false;
  }

  std::string_view rest_;
  bool ok_ = true;
};

// The last length-delimited field `wanted` of a message (protobuf merges
// repeated singular messages; the exporters write one), or nullopt.
std::optional<std::string_view> LastBytesField(std::string_view message, uint32_t wanted) {
  WireReader reader(message);
  uint32_t field = 0, wire = 0;
  uint64_t varint = 0;
  std::string_view bytes;
  std::optional<std::string_view> found;
  while (reader.Next(&field, &wire, &varint, &bytes)) {
    if (field == wanted && wire == kWireBytes) found = bytes;
  }
  if (!reader.ok()) return std::nullopt;
  return found;
}

// TensorShapeProto -> dims (-1 for a symbolic or unset dimension).
std::optional<std::vector<int64_t>> ShapeDims(std::string_view shape) {
  std::vector<int64_t> dims;
  WireReader reader(shape);
  uint32_t field = 0, wire = 0;
  uint64_t varint = 0;
  std::string_view dim;
  while (reader.Next(&field, &wire, &varint, &dim)) {
    if (field != kShapeDim || wire != kWireBytes) continue;
    int64_t size = -1;
    WireReader dim_reader(dim);
    uint32_t dim_field = 0, dim_wire = 0;
    uint64_t value = 0;
    std::string_view unused;
    while (dim_reader.Next(&dim_field, &dim_wire, &value, &unused)) {
      if (dim_field == kDimValue && dim_wire == kWireVarint) size = static_cast<int64_t>(value);
    }
    if (!dim_reader.ok()) return std::nullopt;
    dims.push_back(size);
  }
  if (!reader.ok()) return std::nullopt;
  return dims;
}

std::optional<OnnxDeclaredInput> ParseValueInfo(std::string_view value_info) {
  OnnxDeclaredInput input;
  const auto name = LastBytesField(value_info, kValueInfoName);
  if (name) input.name = std::string(*name);
  const auto type = LastBytesField(value_info, kValueInfoType);
  const auto tensor = type ? LastBytesField(*type, kTypeTensor) : std::nullopt;
  const auto shape = tensor ? LastBytesField(*tensor, kTensorTypeShape) : std::nullopt;
  if (!shape) return input;
  const auto dims = ShapeDims(*shape);
  if (!dims) return std::nullopt;
  input.has_shape = true;
  input.dims = *dims;
  return input;
}

}  // namespace

std::string OnnxDeclaredInput::ToString() const {
  if (!has_shape) return "unknown";
  std::string text;
  for (size_t i = 0; i < dims.size(); ++i) {
    if (i > 0) text += "x";
    text += dims[i] < 0 ? "?" : std::to_string(dims[i]);
  }
  return text.empty() ? "a scalar" : text;
}

std::optional<OnnxDeclaredInput> ReadOnnxDeclaredInput(const char* bytes, size_t size) {
  if (bytes == nullptr) return std::nullopt;
  const auto graph = LastBytesField(std::string_view(bytes, size), kModelGraph);
  if (!graph) return std::nullopt;
  std::vector<std::string_view> inputs;
  std::vector<std::string> initializers;
  WireReader reader(*graph);
  uint32_t field = 0, wire = 0;
  uint64_t varint = 0;
  std::string_view message;
  while (reader.Next(&field, &wire, &varint, &message)) {
    if (wire != kWireBytes) continue;
    if (field == kGraphInput) inputs.push_back(message);
    if (field == kGraphInitializer) {
      const auto name = LastBytesField(message, kTensorName);
      if (name) initializers.emplace_back(*name);
    }
  }
  if (!reader.ok()) return std::nullopt;
  for (const std::string_view value_info : inputs) {
    auto input = ParseValueInfo(value_info);
    if (!input) return std::nullopt;
    if (std::find(initializers.begin(), initializers.end(), input->name) == initializers.end()) {
      return input;
    }
  }
  return std::nullopt;
}

}  // namespace duskmap
