// raykernel/io/number.hpp: reading one number token the way every raykernel text format does.
//
// docs/contract.md §3 and §7: a number is anything C's strtod accepts in the "C" locale — decimal, scientific,
// hexadecimal with a 0x prefix (`0x1.8p3`), an optional leading sign, leading or trailing dots (`.5`, `5.`)
// — read with correct rounding to the nearest double (ties to even). It must be finite, must not overflow
// when read, and a nonzero value must not round to zero (`1e-400` is an error; `4e-324` reads as the
// smallest subnormal). The whole token must be the number: `1.5x` and `0x` are not numbers.
//
// Decimal text goes through std::from_chars (correctly rounded and locale-free in GCC 12: the fast_float
// algorithm with an exact big-decimal fallback); hexadecimal text through std::from_chars' hex format.
// tests/io_number_test.cpp checks both against glibc's strtod on every number form.
#pragma once

#include <cstdint>
#include <string_view>

namespace raykernel::io {

enum class NumberError : std::uint8_t {
  none,
  not_a_number,  // the token is not (entirely) a number in strtod syntax
  non_finite,    // inf, infinity, nan, nan(...)
  overflow,      // finite text whose value is beyond the largest double
  underflow,     // nonzero text whose value rounds to zero
};

struct NumberParse {
  double value = 0;  // the correctly rounded value when error == none
  NumberError error = NumberError::not_a_number;
  [[nodiscard]] bool ok() const noexcept { return error == NumberError::none; }
};

// Reads `token` (no surrounding blanks) as one number under the rules above. Never throws.
[[nodiscard]] NumberParse parse_double(std::string_view token) noexcept;

// Reads `token` as a decimal integer (optional sign; no other characters) in [min, max]. Never throws.
[[nodiscard]] bool parse_integer(std::string_view token, std::int64_t min, std::int64_t max,
                                 std::int64_t& value) noexcept;

// "is not a number", "is not finite", "overflows the double range", "is nonzero but rounds to zero".
[[nodiscard]] std::string_view describe(NumberError error) noexcept;

}  // namespace raykernel::io
