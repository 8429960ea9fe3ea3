// What a call rejects: the message of the invalid_input it throws, or "(valid)" when it returns. For tests that
// check the reason an entry point names for each kind of invalid input.
#pragma once

#include <raykernel/core.hpp>

#include <functional>
#include <string>

namespace raykernel::test {

inline std::string invalid_reason(const std::function<void()>& call) {
  try {
    call();
  } catch (const invalid_input& e) {
    return e.what();
  }
  return "(valid)";
}

}  // namespace raykernel::test
