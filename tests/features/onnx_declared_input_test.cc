#include "slam/features/onnx_declared_input.h"

#include <cstdint>
#include <string>

#include <gtest/gtest.h>

#include "slam/features/embedded_model.h"

namespace duskmap {
namespace {

// Protobuf wire format, written by hand so that the reader is checked
// against bytes whose meaning the test states.
std::string Varint(uint64_t v) {
  std::string out;
  do {
    uint8_t byte = v & 0x7f;
    v >>= 7;
    if (v) byte |= 0x80;
    out.push_back(static_cast<char>(byte));
  } while (v);
  return out;
}
std::string Bytes(uint32_t field, const std::string& payload) {
  return Varint(field << 3 | 2) + Varint(payload.size()) + payload;
}
std::string Number(uint32_t field, uint64_t value) { return Varint(field << 3) + Varint(value); }

// TensorShapeProto.Dimension: dim_value (1) or dim_param (2).
std::string Dim(int64_t value) { return Bytes(1, Number(1, static_cast<uint64_t>(value))); }
std::string SymbolicDim(const std::string& name) { return Bytes(1, Bytes(2, name)); }
// ValueInfoProto{name, type{tensor_type{elem_type FLOAT, shape{dims}}}}.
std::string Input(const std::string& name, const std::string& dims) {
  return Bytes(11, Bytes(1, name) + Bytes(2, Bytes(1, Number(1, 1) + Bytes(2, dims))));
}
// ModelProto{ir_version 6, graph{...}}.
std::string Model(const std::string& graph) { return Number(1, 6) + Bytes(7, graph); }

std::optional<OnnxDeclaredInput> Read(const std::string& bytes) {
  return ReadOnnxDeclaredInput(bytes.data(), bytes.size());
}

TEST(OnnxDeclaredInput, ReadsTheFirstInputThatIsNotAnInitializer) {
  // An older exporter's graph: the weight W is listed as an input too, first.
  const std::string initializer = Bytes(5, Bytes(8, "W") + Number(2, 1));  // TensorProto{name, data_type}
  const std::string graph = Bytes(1, "node-bytes") + initializer + Input("W", Dim(16) + Dim(4096)) +
                            Input("patches", SymbolicDim("N") + Dim(1) + Dim(64) + Dim(64));
  const auto input = Read(Model(graph));
  ASSERT_TRUE(input.has_value());
  EXPECT_EQ(input->name, "patches");
  EXPECT_TRUE(input->has_shape);
  EXPECT_EQ(input->dims, (std::vector<int64_t>{-1, 1, 64, 64}));
  EXPECT_EQ(input->ToString(), "?x1x64x64");
}

TEST(OnnxDeclaredInput, AnInputWithoutAShapeDeclaresNone) {
  const auto input = Read(Model(Bytes(11, Bytes(1, "x"))));
  ASSERT_TRUE(input.has_value());
  EXPECT_EQ(input->name, "x");
  EXPECT_FALSE(input->has_shape);
  EXPECT_EQ(input->ToString(), "unknown");
}

TEST(OnnxDeclaredInput, MalformedBytesAndModelsWithoutInputsGiveNothing) {
  const std::string model = Model(Input("patches", Dim(2) + Dim(1) + Dim(32) + Dim(32)));
  EXPECT_TRUE(Read(model).has_value());
  for (size_t cut = 1; cut < model.size(); ++cut) {
    EXPECT_FALSE(Read(model.substr(0, cut)).has_value()) << cut;
  }
  EXPECT_FALSE(Read("not a protobuf").has_value());
  EXPECT_FALSE(Read(Model(Bytes(1, "a graph with only a node"))).has_value());
  EXPECT_FALSE(Read("").has_value());
  EXPECT_FALSE(ReadOnnxDeclaredInput(nullptr, 0).has_value());
}

TEST(OnnxDeclaredInput, TheEmbeddedDuskNetModelDeclaresBatchesOf32x32GrayPatches) {
  const EmbeddedModel& model = EmbeddedDuskNetModel();
  const auto input = ReadOnnxDeclaredInput(model.bytes, model.size);
  ASSERT_TRUE(input.has_value());
  ASSERT_EQ(input->dims.size(), 4u) << input->ToString();
  EXPECT_LT(input->dims[0], 0) << "the batch is dynamic";
  EXPECT_EQ(input->dims[1], 1);
  EXPECT_EQ(input->dims[2], 32);
  EXPECT_EQ(input->dims[3], 32);
}

}  // namespace
}  // namespace duskmap
