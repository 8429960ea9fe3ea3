// The text formats of the CLI (docs/contract.md §3–§4): lines of numbers in strtod syntax, and doubles printed so
// that strtod reads them back exactly.
#pragma once

#include <array>
#include <string>
#include <string_view>

namespace raykernel::cli {

inline constexpr int max_numbers_per_line = 15;  // triangle lines (docs/contract.md §6)

enum class LineStatus { skip, numbers, invalid };

struct NumberLine {
  LineStatus status = LineStatus::skip;
  std::array<double, max_numbers_per_line> value{};  // the first `expected` entries, when status == numbers
  std::string reason;                                // when status == invalid
};

// Reads a line of exactly `expected` (≤ max_numbers_per_line) finite numbers separated by blanks (space, tab, CR, VT, FF).
// Blank lines and lines whose first non-blank character is '#' are `skip`. A number is anything C's strtod
// accepts in the "C" locale (decimal, scientific, hexadecimal with 0x) that is finite and does not overflow
// when read; underflow to a subnormal or zero is accepted, as strtod rounds it. Anything else is `invalid`
// with a reason naming the field.
[[nodiscard]] NumberLine parse_number_line(std::string_view line, int expected);

// The shortest decimal text that strtod reads back as exactly x ("inf", "-inf", "-0" included).
[[nodiscard]] std::string format_shortest(double x);
// A hexadecimal float ("0x1.8p+1", "-0x0p+0", "inf"), exact by construction.
[[nodiscard]] std::string format_hex(double x);

}  // namespace raykernel::cli
