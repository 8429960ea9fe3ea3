#include "fuzz_text.hpp"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace raykernel::fuzz {

std::vector<std::string_view> getline_lines(std::string_view text) {
  std::vector<std::string_view> lines;
  std::size_t start = 0;
  while (start < text.size()) {
    const std::size_t end = text.find('\n', start);
    if (end == std::string_view::npos) {
      lines.push_back(text.substr(start));
      break;
    }
    lines.push_back(text.substr(start, end - start));
    start = end + 1;
  }
  return lines;
}

std::vector<std::string_view> input_lines(std::string_view text) {
  if (text.starts_with("\xEF\xBB\xBF")) text.remove_prefix(3);
  return getline_lines(text);
}

bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

std::vector<std::string_view> tokens_of(std::string_view line) {
  std::vector<std::string_view> tokens;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && is_blank(line[i])) ++i;
    const std::size_t start = i;
    while (i < line.size() && !is_blank(line[i])) ++i;
    if (i > start) tokens.push_back(line.substr(start, i - start));
  }
  return tokens;
}

ExpectedNumbers expected_numbers(std::string_view line, std::size_t count) {
  ExpectedNumbers e;
  const std::vector<std::string_view> tokens = tokens_of(line);
  if (tokens.empty() || tokens[0][0] == '#') {
    e.skipped = true;
    return e;
  }
  if (tokens.size() != count || count > e.value.size()) return e;
  for (std::size_t k = 0; k < count; ++k) {
    const std::string token(tokens[k]);
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(token.c_str(), &end);
    const bool overflowed = errno == ERANGE && std::isinf(v);
    const bool underflowed_to_zero = errno == ERANGE && v == 0;
    if (end != token.c_str() + token.size() || !std::isfinite(v) || overflowed || underflowed_to_zero) return e;
    e.value[k] = v;
  }
  e.numbers = true;
  return e;
}

std::string c_escaped(std::string_view text) {
  std::string s = "\"";
  for (unsigned char c : text) {
    if (c == '\n') {
      s += "\\n\"\n\"";
    } else if (c == '\\' || c == '"') {
      s += '\\';
      s += static_cast<char>(c);
    } else if (c < 0x20 || c >= 0x7f) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02x\"\"", c);
      s += buf;
    } else {
      s += static_cast<char>(c);
    }
  }
  return s + "\"";
}

}  // namespace raykernel::fuzz
