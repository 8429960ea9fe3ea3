// A fact about number texts that the query, planes and rays files (strtod syntax) and scene files (JSON
// numbers, a subset of it) both need: whether a number's text denotes a nonzero value. A nonzero number
// that rounds to zero when read is an error (docs/contract.md §3), not a zero.
#pragma once

#include <string_view>

namespace raykernel::cli {

// Whether `number`, a text strtod reads completely as a finite value (decimal, scientific, or hexadecimal
// with 0x; JSON numbers are decimal), has a nonzero digit in its significand, i.e. denotes a nonzero value
// whatever its exponent: the digits before 'e'/'E' (decimal) or between "0x" and 'p'/'P' (hexadecimal).
[[nodiscard]] inline bool denotes_nonzero(std::string_view number) noexcept {
  std::size_t i = 0;
  if (i < number.size() && (number[i] == '+' || number[i] == '-')) ++i;
  const bool hex = number.size() >= i + 2 && number[i] == '0' && (number[i + 1] == 'x' || number[i + 1] == 'X');
  if (hex) i += 2;
  for (; i < number.size(); ++i) {
    const char c = number[i];
    if (hex ? (c == 'p' || c == 'P') : (c == 'e' || c == 'E')) break;
    if ((c >= '1' && c <= '9') || (hex && ((c >= 'a' && c <= 'f') || (c >= 'A' && c <= 'F')))) return true;
  }
  return false;
}

// The reason given for such a number, after the number itself.
inline constexpr std::string_view rounds_to_zero_reason =
    "is nonzero but rounds to zero when read (its magnitude is at most 2^-1075, half the smallest subnormal)";

}  // namespace raykernel::cli
