// Float descriptors in 8 bits per element, the form in which the map keeps
// node descriptors and the vocabulary may keep its words: each row gets its
// own offset and step, value = offset + step * code with code in [0, 255],
// step = (row max - row min) / 255, so the error is at most step / 2.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

namespace duskmap {

enum class DescriptorStorage {
  kFloat32,  // float descriptors as extracted
  kUint8,    // float descriptors quantized to 8 bits per element (per-row offset, step)
};

const char* DescriptorStorageName(DescriptorStorage storage);
// The storage named "float32" or "uint8"; nullopt for any other name (for
// callers that report it with their own field or file).
std::optional<DescriptorStorage> DescriptorStorageFromName(const std::string& name);
// Throws ConfigError for an unknown name.
DescriptorStorage ParseDescriptorStorage(const std::string& name);

struct RowScale {
  float offset = 0.0f;  // the row's minimum
  float step = 0.0f;    // (max - min) / 255; 0 for a constant row
};

// Quantizes `cols` floats into `codes`. Returns false, leaving `codes`
// unspecified, when the row holds a non-finite value.
bool QuantizeRow(const float* row, int cols, uint8_t* codes, RowScale* scale);
// offset + step * code for each element.
void DequantizeRow(const uint8_t* codes, int cols, const RowScale& scale, float* row);

}  // namespace duskmap
