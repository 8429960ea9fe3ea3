#include "common/text_input.hpp"

#include "common/io.hpp"
#include "common/text_format.hpp"

#include <raykernel/io/number.hpp>

#include <charconv>
#include <cmath>
#include <cstdio>
#include <istream>
#include <limits>
#include <string>

namespace raykernel::cli {

bool LineReader::next(std::string& line) {
  line.clear();
  if (!in_.good()) return false;
  if (std::ostream* const tied = in_.tie()) tied->flush();  // answers appear as lines are typed (a terminal)
  std::streambuf* const buffer = in_.rdbuf();
  for (;;) {
    const int c = buffer->sbumpc();
    if (c == std::char_traits<char>::eof()) {
      in_.setstate(std::ios::eofbit);
      if (line.empty()) {
        in_.setstate(std::ios::failbit);
        return false;
      }
      break;  // a last line without '\n'
    }
    if (c == '\n') break;
    if (line.size() == limits::max_line_bytes) {
      // Not a text file of lines (/dev/zero, a binary file): stop, and say why (Input::read_error).
      if (auto* fd_buffer = dynamic_cast<FdInputBuffer*>(buffer))
        fd_buffer->fail("line " + with_thousands(line_number_ + 1) + " is longer than " + with_thousands(limits::max_line_bytes) +
                        " bytes, the longest line raykernel reads");
      in_.setstate(std::ios::badbit);
      line.clear();
      return false;
    }
    line += static_cast<char>(c);
  }
  if (++line_number_ == 1 && line.starts_with("\xEF\xBB\xBF")) line.erase(0, 3);
  return true;
}

namespace {

constexpr bool is_blank(char c) noexcept { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

// Why `token` is not a valid number, or empty when it is one (then `value` holds it). The number rules
// (strtod syntax, correctly rounded, finite, not a nonzero that rounds to zero) are the mesh readers' too:
// raykernel::io::parse_double is their one home.
std::string number_problem(std::string_view token, double& value) {
  const io::NumberParse number = io::parse_double(token);
  if (number.ok()) {
    value = number.value;
    return {};
  }
  std::string reason = quote(token, limits::quoted_token_bytes) + " " + std::string(io::describe(number.error));
  if (number.error == io::NumberError::not_a_number && token.find(',') != std::string_view::npos)
    reason += " (separate numbers with blanks, not commas)";
  return reason;
}

struct Token {
  std::string_view text;
  std::size_t column;  // 1-based byte column in the line
};

}  // namespace

namespace {

// strtod's spellings of +inf: "inf" or "infinity", any case, with an optional '+'.
bool is_positive_infinity(std::string_view token) {
  if (token.starts_with('+')) token.remove_prefix(1);
  auto equal_ignoring_case = [](std::string_view a, std::string_view b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i)
      if ((a[i] | 0x20) != b[i]) return false;
    return true;
  };
  return equal_ignoring_case(token, "inf") || equal_ignoring_case(token, "infinity");
}

}  // namespace

NumberLine parse_number_line(std::string_view line, int expected) {
  return parse_number_line(line, expected, expected, 0).line;
}

NumberLineOf parse_number_line(std::string_view line, int expected, int alternative, int infinity_field) {
  NumberLineOf parsed;
  NumberLine& result = parsed.line;
  const int longest = expected > alternative ? expected : alternative;
  Token tokens[max_numbers_per_line + 1];
  int count = 0;
  for (std::size_t i = 0;;) {
    while (i < line.size() && is_blank(line[i])) ++i;
    if (i == line.size()) break;
    if (count == 0 && line[i] == '#') return parsed;  // a comment line
    const std::size_t start = i;
    while (i < line.size() && !is_blank(line[i])) ++i;
    if (count <= longest) tokens[count] = {line.substr(start, i - start), start + 1};
    ++count;
  }
  if (count == 0) return parsed;  // a blank line

  result.status = LineStatus::invalid;
  // The count the line is read against: its own when it is one of the two, else the nearest one above it (or
  // the longest), so that the extra tokens are named from there.
  const int against = count == expected || count == alternative
                          ? count
                          : (count < expected && (count > alternative || expected < alternative) ? expected
                             : count < alternative                                             ? alternative
                                                                                                : longest);
  // A bad token first (it explains a wrong count too: "1,2,3"), then the count.
  const int checked = count < against ? count : against;
  for (int k = 0; k < checked; ++k) {
    double value = 0;
    if (k + 1 == infinity_field && is_positive_infinity(tokens[k].text)) {
      value = std::numeric_limits<double>::infinity();
    } else if (std::string problem = number_problem(tokens[k].text, value); !problem.empty()) {
      result.reason = "field " + std::to_string(k + 1) + ": " + problem;
      return parsed;
    }
    result.value[static_cast<std::size_t>(k)] = value;
  }
  if (count != against) {
    result.reason = "expected " + std::to_string(expected) +
                    (alternative != expected ? " or " + std::to_string(alternative) : std::string()) +
                    " numbers, found " + std::to_string(count);
    if (count > against) {
      const Token& extra = tokens[against];
      std::string_view rest = line.substr(extra.column - 1);
      rest = rest.substr(0, rest.find_last_not_of(" \t\r\v\f") + 1);
      result.reason += "; the extra ones start at token " + std::to_string(against + 1) + ", column " +
                       std::to_string(extra.column) + ": " +
                       quote(rest, limits::quoted_token_bytes);
      if (extra.text.starts_with("#")) result.reason += " (a # comment must be on a line of its own)";
    }
    result.value = {};
    return parsed;
  }
  result.status = LineStatus::numbers;
  parsed.count = count;
  return parsed;
}

NumberLineOf parse_ray_line_with_interval(std::string_view line) {
  NumberLineOf parsed = parse_number_line(line, 6, 8, 8);
  std::string& reason = parsed.line.reason;
  if (reason.starts_with("field 7:")) reason.insert(7, " (t_min)");
  else if (reason.starts_with("field 8:")) reason.insert(7, " (t_max)");
  return parsed;
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

std::string hit_answer(std::size_t index, double t, bool hex) {
  return "hit " + std::to_string(index) + ' ' + (hex ? format_hex(t) : format_shortest(t));
}

}  // namespace raykernel::cli
