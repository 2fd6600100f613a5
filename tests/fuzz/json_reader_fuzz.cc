// libFuzzer target: the one JSON reader (slam/core/json_reader.h). Any input
// either throws duskmap::Error (one line) or gives a value nested at most
// kMaxJsonDepth levels that can be copied, written and read back to the same
// value (nlohmann's copy and dump() recurse once per level: a deeper value
// would overflow the stack, as '[' * 200000 did in every reader).
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "slam/core/check.h"
#include "slam/core/json_reader.h"

namespace {

int Depth(const nlohmann::json& value, int limit) {
  if (limit < 0) std::abort();  // deeper than the reader allows
  int deepest = 0;
  if (value.is_structured()) {
    for (const auto& item : value) deepest = std::max(deepest, Depth(item, limit - 1));
    return deepest + 1;
  }
  return 0;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  nlohmann::json value;
  try {
    value = duskmap::ParseJsonText(text, "fuzz.json");
  } catch (const duskmap::Error& e) {
    const std::string message = e.what();
    if (message.rfind("fuzz.json", 0) != 0 || message.find('\n') != std::string::npos) std::abort();
    return 0;
  }
  if (Depth(value, duskmap::kMaxJsonDepth) > duskmap::kMaxJsonDepth) std::abort();
  const nlohmann::json copy = value;
  const nlohmann::json again = duskmap::ParseJsonText(copy.dump(), "dumped");
  if (again != value) std::abort();
  return 0;
}
