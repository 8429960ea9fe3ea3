#include "text_input.hpp"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace raykernel::cli {
namespace {

constexpr bool is_blank(char c) noexcept { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

// A token as it may be quoted in an error message: at most 40 characters, control bytes escaped.
std::string quoted(std::string_view token) {
  std::string out = "'";
  const std::size_t shown = token.size() > 40 ? 40 : token.size();
  for (std::size_t i = 0; i < shown; ++i) {
    const auto c = static_cast<unsigned char>(token[i]);
    if (c < 0x20 || c == 0x7f) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02x", c);
      out += buf;
    } else {
      out += static_cast<char>(c);
    }
  }
  if (shown < token.size()) out += "...";
  return out + "'";
}

}  // namespace

NumberLine parse_number_line(std::string_view line, int expected) {
  NumberLine result;
  std::string_view tokens[max_numbers_per_line + 1];
  int count = 0;
  std::size_t i = 0;
  while (true) {
    while (i < line.size() && is_blank(line[i])) ++i;
    if (i == line.size()) break;
    if (count == 0 && line[i] == '#') return result;  // a comment line
    const std::size_t start = i;
    while (i < line.size() && !is_blank(line[i])) ++i;
    if (count <= expected) tokens[count] = line.substr(start, i - start);
    ++count;
  }
  if (count == 0) return result;  // a blank line

  result.status = LineStatus::invalid;
  if (count != expected) {
    result.reason = "expected " + std::to_string(expected) + " numbers, found " + std::to_string(count);
    return result;
  }
  std::string buffer;
  for (int k = 0; k < expected; ++k) {
    const std::string_view token = tokens[k];
    const std::string field = "field " + std::to_string(k + 1) + ": ";
    buffer.assign(token);  // strtod needs a terminating NUL; a NUL inside the token stops it early
    char* end = nullptr;
    errno = 0;
    const double value = std::strtod(buffer.c_str(), &end);
    if (end != buffer.c_str() + buffer.size() || token.empty() || is_blank(token.front())) {
      result.reason = field + quoted(token) + " is not a number";
      return result;
    }
    if (errno == ERANGE && std::isinf(value)) {
      result.reason = field + quoted(token) + " overflows the double range (non-finite)";
      return result;
    }
    if (!std::isfinite(value)) {
      result.reason = field + quoted(token) + " is not finite (non-finite)";
      return result;
    }
    result.value[static_cast<std::size_t>(k)] = value;
  }
  result.status = LineStatus::numbers;
  return result;
}

std::string format_shortest(double x) {
  char buf[64];
  const std::to_chars_result r = std::to_chars(buf, buf + sizeof buf, x);
  return std::string(buf, r.ptr);
}

std::string format_hex(double x) {
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%a", x);
  return buf;
}

}  // namespace raykernel::cli
