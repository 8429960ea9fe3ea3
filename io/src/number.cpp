// The number reader of <raykernel/io/number.hpp>.
#include <raykernel/io/number.hpp>

#include <charconv>
#include <cmath>
#include <system_error>

namespace raykernel::io {
namespace {

constexpr bool is_digit(char c) noexcept { return c >= '0' && c <= '9'; }
constexpr bool is_hex_digit(char c) noexcept {
  return is_digit(c) || (c >= 'a' && c <= 'f') || (c >= 'A' && c <= 'F');
}

// std::from_chars reports overflow and underflow to zero alike (result_out_of_range, value untouched). Which
// one it was follows from the order of magnitude of the text: the position of its first nonzero digit
// relative to the radix point, plus the exponent. Values this far out of range (below 2^-1075 or at least
// 2^1024) have an order of magnitude far from 0, so its sign decides, whatever the base. `digits` is the
// mantissa (without sign and prefix), `exponent_mark` 'e' or 'p', `digit_weight` 1 for decimal, 4 for hex
// (the hex exponent counts binary digits).
bool magnitude_is_large(std::string_view text, char exponent_mark, long digit_weight) noexcept {
  long position = 0;  // the order of magnitude, in digits, of the first nonzero digit
  bool seen_point = false, seen_nonzero = false;
  std::size_t i = 0;
  long integer_digits = 0, leading_fraction_zeros = 0;
  for (; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '.') {
      seen_point = true;
    } else if (c == exponent_mark || c == (exponent_mark - 'a' + 'A')) {
      break;
    } else if (!seen_point) {
      if (seen_nonzero || c != '0') {
        seen_nonzero = true;
        ++integer_digits;
      }
    } else if (!seen_nonzero) {
      if (c == '0') ++leading_fraction_zeros;
      else seen_nonzero = true;
    }
  }
  position = integer_digits > 0 ? integer_digits : -leading_fraction_zeros;
  long exponent = 0;
  if (i < text.size()) {  // the exponent, saturated (its digits were validated by from_chars)
    ++i;
    bool negative = false;
    if (i < text.size() && (text[i] == '+' || text[i] == '-')) negative = text[i++] == '-';
    for (; i < text.size() && is_digit(text[i]); ++i) {
      if (exponent < 100'000'000) exponent = exponent * 10 + (text[i] - '0');
    }
    if (negative) exponent = -exponent;
  }
  return position * digit_weight + exponent > 0;
}

}  // namespace

NumberParse parse_double(std::string_view token) noexcept {
  NumberParse result;
  std::string_view rest = token;
  bool negative = false;
  if (!rest.empty() && (rest.front() == '+' || rest.front() == '-')) {
    negative = rest.front() == '-';
    rest.remove_prefix(1);
  }
  if (rest.empty()) return result;
  const bool hex = rest.size() >= 2 && rest[0] == '0' && (rest[1] == 'x' || rest[1] == 'X');
  if (hex) rest.remove_prefix(2);
  // What may start the mantissa: strtod's syntax, minus the forms from_chars would accept beyond it (a second
  // sign, or "inf" after "0x").
  const char first = rest.empty() ? '\0' : rest.front();
  const bool starts_number = hex ? (is_hex_digit(first) || first == '.') : (is_digit(first) || first == '.');
  if (!starts_number) {
    if (!hex && !rest.empty()) {
      // inf, infinity, nan, nan(chars): strtod reads them; they are not finite.
      double special = 0;
      const auto r = std::from_chars(rest.data(), rest.data() + rest.size(), special);
      if (r.ec == std::errc{} && r.ptr == rest.data() + rest.size() && !std::isfinite(special)) {
        result.error = NumberError::non_finite;
      }
    }
    return result;
  }
  double value = 0;
  const auto format = hex ? std::chars_format::hex : std::chars_format::general;
  const auto r = std::from_chars(rest.data(), rest.data() + rest.size(), value, format);
  if (r.ptr != rest.data() + rest.size()) return result;  // trailing characters (or nothing read)
  if (r.ec == std::errc::result_out_of_range) {
    result.error = magnitude_is_large(rest, hex ? 'p' : 'e', hex ? 4 : 1) ? NumberError::overflow
                                                                           : NumberError::underflow;
    return result;
  }
  if (r.ec != std::errc{}) return result;
  if (!std::isfinite(value)) {  // from_chars' own overflow report, should a version report it this way
    result.error = NumberError::overflow;
    return result;
  }
  if (value == 0) {
    // A zero result from text with a nonzero digit is an underflow (GCC 12 reports it as out of range, but
    // the contract should not depend on that).
    for (char c : rest) {
      if (c == (hex ? 'p' : 'e') || c == (hex ? 'P' : 'E')) break;
      if (c != '0' && c != '.') {
        result.error = NumberError::underflow;
        return result;
      }
    }
  }
  result.value = negative ? -value : value;
  result.error = NumberError::none;
  return result;
}

bool parse_integer(std::string_view token, std::int64_t min, std::int64_t max, std::int64_t& value) noexcept {
  if (!token.empty() && token.front() == '+') {
    token.remove_prefix(1);
    if (token.empty() || !is_digit(token.front())) return false;
  }
  std::int64_t v = 0;
  const auto r = std::from_chars(token.data(), token.data() + token.size(), v);
  if (r.ec != std::errc{} || r.ptr != token.data() + token.size() || v < min || v > max) return false;
  value = v;
  return true;
}

std::string_view describe(NumberError error) noexcept {
  switch (error) {
    case NumberError::none: return "is a number";
    case NumberError::not_a_number: return "is not a number";
    case NumberError::non_finite: return "is not finite";
    case NumberError::overflow: return "overflows the double range";
    case NumberError::underflow:
      return "is nonzero but rounds to zero when read (its magnitude is at most 2^-1075, half the smallest subnormal)";
  }
  return "is not a number";
}

}  // namespace raykernel::io
