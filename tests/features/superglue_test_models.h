// Test models for the SuperGlue tests (onnx_test_models.h explains how they
// are written).
#pragma once

#include <string>

#include "tests/features/onnx_test_models.h"

namespace duskmap::testing {

inline std::string MakeSuperGlueModel(const std::string& file, const std::string& flags = "",
                                      const std::string& test_vector_dir = "") {
  return RunModelScript("make_test_superglue_onnx.py", file, flags, test_vector_dir);
}

}  // namespace duskmap::testing
