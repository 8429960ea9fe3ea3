// The number reader of <raykernel/io/number.hpp>.
#include <raykernel/io/number.hpp>

#include <cerrno>
#include <cfenv>
#include <charconv>
#include <clocale>
#include <cmath>
#include <cstdlib>
#include <string>
#include <system_error>
#if defined(__SSE2__)
#include <xmmintrin.h>  // _mm_getcsr
#endif

#if defined(__cpp_lib_to_chars) && __cpp_lib_to_chars >= 201611L
#define RAYKERNEL_IO_FLOAT_FROM_CHARS 1
#else
#include <locale.h>  // newlocale, strtod_l (glibc)
#define RAYKERNEL_IO_FLOAT_FROM_CHARS 0
#endif

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

// strtod's exponent: the mark, at most one sign, then only digits, at least one. (libstdc++ 12's from_chars
// also takes "0x1p+-3" and reads -3: fuzz_cli found it.)
bool exponent_well_formed(std::string_view text, bool hex) noexcept {
  const std::size_t mark = text.find_first_of(hex ? "pP" : "eE");
  if (mark == std::string_view::npos) return true;
  std::size_t i = mark + 1;
  if (i < text.size() && (text[i] == '+' || text[i] == '-')) ++i;
  if (i == text.size()) return false;
  for (; i < text.size(); ++i)
    if (!is_digit(text[i])) return false;
  return true;
}

// One number's digits (`text`: without sign, and without the 0x prefix when `hex`), read whole.
struct DigitsRead {
  bool whole = false;         // the entire text is a number of the form
  bool out_of_range = false;  // overflow, or a nonzero value that rounded to zero
  double value = 0;
};

#if RAYKERNEL_IO_FLOAT_FROM_CHARS
DigitsRead read_digits(std::string_view text, bool hex) noexcept {
  DigitsRead d;
  const auto format = hex ? std::chars_format::hex : std::chars_format::general;
  const auto r = std::from_chars(text.data(), text.data() + text.size(), d.value, format);
  d.whole = r.ptr == text.data() + text.size() && (r.ec == std::errc{} || r.ec == std::errc::result_out_of_range);
  d.out_of_range = r.ec == std::errc::result_out_of_range;
  return d;
}
#else
// A standard library without floating-point from_chars (libc++ 14, which the ClusterFuzzLite build uses):
// glibc's strtod_l in the "C" locale, also correctly rounded to nearest (under DefaultRounding below).
DigitsRead read_digits(std::string_view text, bool hex) noexcept {
  static const locale_t c_locale = newlocale(LC_ALL_MASK, "C", locale_t{});
  DigitsRead d;
  std::string s;
  try {
    s.reserve(text.size() + 2);
    if (hex) s += "0x";
    s.append(text);
  } catch (...) {
    return d;
  }
  char* end = nullptr;
  const int saved = errno;
  errno = 0;
  d.value = strtod_l(s.c_str(), &end, c_locale);
  const bool range = errno == ERANGE;
  errno = saved;
  d.whole = end == s.c_str() + s.size();
  d.out_of_range = std::isinf(d.value) || (range && d.value == 0);
  return d;
}
#endif

// strtod rounds in the caller's rounding mode, and from_chars' fast path multiplies in it; the contract
// reads to nearest. When the caller's environment is not the default one (rounding, FTZ/DAZ, unmasked
// traps), install the default for the read and restore the caller's afterwards; otherwise cost nothing but
// the check.
class DefaultRounding {
 public:
  DefaultRounding() noexcept {
    bool default_environment = std::fegetround() == FE_TONEAREST;
#if defined(__SSE2__)
    default_environment = default_environment && (_mm_getcsr() & ~0x3Fu) == 0x1F80u;
#endif
    if (!default_environment) {
      std::fegetenv(&caller_);
      std::fesetenv(FE_DFL_ENV);
      installed_ = true;
    }
  }
  ~DefaultRounding() {
    if (installed_) std::fesetenv(&caller_);
  }
  DefaultRounding(const DefaultRounding&) = delete;
  DefaultRounding& operator=(const DefaultRounding&) = delete;

 private:
  std::fenv_t caller_{};
  bool installed_ = false;
};

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
      const DigitsRead special = read_digits(rest, false);
      if (special.whole && !special.out_of_range && !std::isfinite(special.value)) {
        result.error = NumberError::non_finite;
      }
    }
    return result;
  }
  if (!exponent_well_formed(rest, hex)) return result;
  const DefaultRounding rounding;
  const DigitsRead read = read_digits(rest, hex);
  if (!read.whole) return result;  // trailing characters (or nothing read)
  if (read.out_of_range) {
    result.error = magnitude_is_large(rest, hex ? 'p' : 'e', hex ? 4 : 1) ? NumberError::overflow
                                                                           : NumberError::underflow;
    return result;
  }
  const double value = read.value;
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
