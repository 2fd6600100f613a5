#include "slam/features/descriptor_quantization.h"

#include <algorithm>
#include <cmath>

#include "slam/core/check.h"

namespace duskmap {

const char* DescriptorStorageName(DescriptorStorage storage) {
  switch (storage) {
    case DescriptorStorage::kFloat32: return "float32";
    case DescriptorStorage::kUint8: return "uint8";
  }
  return "unknown";
}

std::optional<DescriptorStorage> DescriptorStorageFromName(const std::string& name) {
  for (DescriptorStorage s : {DescriptorStorage::kFloat32, DescriptorStorage::kUint8}) {
    if (name == DescriptorStorageName(s)) return s;
  }
  return std::nullopt;
}

DescriptorStorage ParseDescriptorStorage(const std::string& name) {
  const std::optional<DescriptorStorage> storage = DescriptorStorageFromName(name);
  SLAM_THROW_IF_NOT(ConfigError, storage.has_value())
      << "descriptor storage '" << name << "' is not one of float32, uint8";
  return *storage;
}

bool QuantizeRow(const float* row, int cols, uint8_t* codes, RowScale* scale) {
  if (cols <= 0) return true;
  float lo = row[0], hi = row[0];
  for (int k = 0; k < cols; ++k) {
    if (!std::isfinite(row[k])) return false;  // min/max would skip a NaN
    lo = std::min(lo, row[k]);
    hi = std::max(hi, row[k]);
  }
  const float step = (hi - lo) / 255.0f;
  scale->offset = lo;
  scale->step = step;
  for (int k = 0; k < cols; ++k) {
    codes[k] = step > 0.0f ? static_cast<uint8_t>(std::lround((row[k] - lo) / step)) : 0;
  }
  return true;
}

void DequantizeRow(const uint8_t* codes, int cols, const RowScale& scale, float* row) {
  for (int k = 0; k < cols; ++k) row[k] = scale.offset + scale.step * codes[k];
}

}  // namespace duskmap
