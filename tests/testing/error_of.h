// Test support shared by the suites (tests/testing/): the one-line message of
// the duskmap::Error a call throws.
#pragma once

#include <string>

#include "slam/core/check.h"

namespace duskmap::testing {

// The message of the duskmap::Error that `fn` throws, or "" when none.
template <typename Fn>
std::string ErrorOf(Fn&& fn) {
  try {
    fn();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace duskmap::testing
