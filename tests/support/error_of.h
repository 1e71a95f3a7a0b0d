#pragma once
// The message of the welkin::Error that `f` throws, or "no error": for tests that check what a
// failure says (the file, the path inside it).
#include <functional>
#include <string>

#include "welkin/core/error.h"

namespace welkin::testing {

inline std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const welkin::Error& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace welkin::testing
