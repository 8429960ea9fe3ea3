// Doubles in the library's messages, written the same way whatever the floating-point environment:
// std::to_chars gives the shortest text that reads back to the same double, by integer arithmetic only
// (printf's %g follows the x87 rounding mode a caller may have changed, so its digits would depend on it).
#pragma once

#include <raykernel/raykernel.hpp>

#include <charconv>
#include <string>

namespace raykernel::detail {

[[nodiscard]] inline std::string shortest_text(double x) {
  char buf[32];
  const std::to_chars_result r = std::to_chars(buf, buf + sizeof buf, x);
  return std::string(buf, r.ptr);
}

// Appended piece by piece: GCC 12 warns (-Wrestrict, a false positive of its string insert) on "(" + std::string&&
// once this is inlined into some callers.
[[nodiscard]] inline std::string shortest_text(const Vec3& v) {
  std::string s = "(";
  s += shortest_text(v.x);
  s += ", ";
  s += shortest_text(v.y);
  s += ", ";
  s += shortest_text(v.z);
  s += ')';
  return s;
}

}  // namespace raykernel::detail
