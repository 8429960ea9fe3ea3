// The number reader of <raykernel/io/number.hpp> against glibc's strtod (correctly rounded in the "C"
// locale), on every number form: decimal and scientific, hexadecimal floats, subnormals, exact halfway
// cases between neighbouring doubles and strings a digit away from them, long digit strings, leading '+',
// leading and trailing dots, and malformed tokens. The oracle's verdict comes from strtod alone: the whole
// token consumed, errno == ERANGE with ±inf (overflow) or with 0 (a nonzero value rounding to zero), inf or
// NaN without ERANGE (non-finite text); otherwise the value, bit for bit (the sign of zero included).
#include <raykernel/io/number.hpp>

#include <gmpxx.h>
#include <gtest/gtest.h>

#include <bit>
#include <cctype>
#include <cerrno>
#include <cfenv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <random>
#include <string>
#include <vector>
#if defined(__SSE2__)
#include <xmmintrin.h>
#endif

namespace raykernel::io {
namespace {

struct Expected {
  NumberError error;
  double value;
};

Expected strtod_verdict(const std::string& s) {
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(s.c_str(), &end);
  const bool range = errno == ERANGE;
  if (s.empty() || end != s.c_str() + s.size() || std::isspace(static_cast<unsigned char>(s.front())))
    return {NumberError::not_a_number, 0};  // (tokens never start with a blank)
  if (std::isnan(v)) return {NumberError::non_finite, 0};
  if (std::isinf(v)) return {range ? NumberError::overflow : NumberError::non_finite, 0};
  if (v == 0 && range) return {NumberError::underflow, 0};
  return {NumberError::none, v};
}

// Compares one token; returns false (and reports) on a disagreement.
bool agrees(const std::string& s) {
  const Expected e = strtod_verdict(s);
  const NumberParse got = parse_double(s);
  if (got.error != e.error) {
    ADD_FAILURE() << "'" << s << "': parse_double says '" << describe(got.error) << "', strtod says '" << describe(e.error) << "'";
    return false;
  }
  if (e.error == NumberError::none && std::bit_cast<std::uint64_t>(got.value) != std::bit_cast<std::uint64_t>(e.value)) {
    char a[64], b[64];
    std::snprintf(a, sizeof a, "%a", got.value);
    std::snprintf(b, sizeof b, "%a", e.value);
    ADD_FAILURE() << "'" << s << "': parse_double " << a << ", strtod " << b;
    return false;
  }
  return true;
}

TEST(NumberReader, HandPickedForms) {
  // Each verdict below is checked against strtod too; the comments give the expected values by hand.
  struct Case { const char* text; NumberError error; double value; };
  const Case cases[] = {
      {"0", NumberError::none, 0.0},
      {"-0", NumberError::none, -0.0},
      {"+1.5", NumberError::none, 1.5},
      {".5", NumberError::none, 0.5},
      {"5.", NumberError::none, 5.0},
      {"-.25e1", NumberError::none, -2.5},
      {"0x1.8p3", NumberError::none, 12.0},           // 1.5 · 2^3
      {"0X.8P1", NumberError::none, 1.0},             // 0.5 · 2
      {"-0x10", NumberError::none, -16.0},            // hex without an exponent
      {"0x1p-1074", NumberError::none, std::numeric_limits<double>::denorm_min()},
      {"4.9406564584124654e-324", NumberError::none, std::numeric_limits<double>::denorm_min()},
      {"2.4703282292062328e-324", NumberError::none, std::numeric_limits<double>::denorm_min()},  // just above half of it
      {"2.4703282292062327e-324", NumberError::underflow, 0},   // just below half: rounds to 0
      {"1e-400", NumberError::underflow, 0},
      {"-2e-324", NumberError::underflow, 0},
      {"0e-400", NumberError::none, 0.0},             // zero is not an underflow
      {"0x0p-9999", NumberError::none, 0.0},
      {"1.7976931348623157e308", NumberError::none, std::numeric_limits<double>::max()},
      {"1.7976931348623158e308", NumberError::none, std::numeric_limits<double>::max()},  // below max + half ulp
      {"1.8e308", NumberError::overflow, 0},
      {"0x1p1024", NumberError::overflow, 0},
      {"1e400", NumberError::overflow, 0},
      {"inf", NumberError::non_finite, 0},
      {"-Infinity", NumberError::non_finite, 0},
      {"nan", NumberError::non_finite, 0},
      {"nan(123)", NumberError::non_finite, 0},
      {"", NumberError::not_a_number, 0},
      {".", NumberError::not_a_number, 0},
      {"+", NumberError::not_a_number, 0},
      {"1e", NumberError::not_a_number, 0},
      {"1e+", NumberError::not_a_number, 0},
      {"0x", NumberError::not_a_number, 0},
      {"0xp1", NumberError::not_a_number, 0},
      {"0x-1", NumberError::not_a_number, 0},
      {"0xinf", NumberError::not_a_number, 0},
      {"+-1", NumberError::not_a_number, 0},
      {"--1", NumberError::not_a_number, 0},
      {"1.2.3", NumberError::not_a_number, 0},
      {"1,5", NumberError::not_a_number, 0},
      {"1p3", NumberError::not_a_number, 0},          // a binary exponent needs 0x
      {"1.5x", NumberError::not_a_number, 0},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.text);
    const NumberParse p = parse_double(c.text);
    EXPECT_EQ(p.error, c.error) << describe(p.error);
    if (c.error == NumberError::none) {
      EXPECT_EQ(std::bit_cast<std::uint64_t>(p.value), std::bit_cast<std::uint64_t>(c.value));
    }
    EXPECT_TRUE(agrees(c.text));
  }
}

// The exact decimal expansion of the dyadic rational n · 2^e, as "DIGITSe-K" (exact, no rounding).
std::string exact_decimal(const mpz_class& n, long e) {
  if (e >= 0) {
    mpz_class v = n;
    v <<= static_cast<mp_bitcnt_t>(e);
    return v.get_str();
  }
  mpz_class five;  // n · 2^e = n · 5^-e / 10^-e
  mpz_ui_pow_ui(five.get_mpz_t(), 5, static_cast<unsigned long>(-e));
  const mpz_class digits = n * five;
  return digits.get_str() + "e" + std::to_string(e);
}

// The exact midpoint between x > 0 and its successor, as decimal text.
std::string midpoint_text(double x) {
  int exp = 0;
  const double m = std::frexp(x, &exp);  // x = m · 2^exp, m in [0.5, 1)
  // x = M · 2^(exp − 53) with M = m · 2^53 (subnormals: the exponent is clamped to −1074)
  long e = exp - 53;
  mpz_class M;
  if (e < -1074) {
    M = static_cast<unsigned long>(std::ldexp(x, 1074));
    e = -1074;
  } else {
    M = static_cast<unsigned long>(std::ldexp(m, 53));
  }
  // midpoint = (2M + 1) · 2^(e − 1)
  return exact_decimal(2 * M + 1, e - 1);
}

TEST(NumberReader, AgreesWithStrtodOnGeneratedStrings) {
  std::mt19937_64 rng(20261123);
  std::printf("number reader: seed 20261123\n");
  auto pick = [&](std::uint64_t n) { return static_cast<std::size_t>(rng() % n); };
  auto digits = [&](std::size_t count, bool hex) {
    std::string s;
    for (std::size_t i = 0; i < count; ++i) s += (hex ? "0123456789abcdefABCDEF" : "0123456789")[pick(hex ? 22 : 10)];
    return s;
  };
  std::size_t checked = 0, failures = 0;
  auto check = [&](const std::string& s) {
    ++checked;
    if (!agrees(s) && ++failures > 20) FAIL() << "too many failures";
  };
  const char* signs[] = {"", "+", "-"};
  for (int i = 0; i < 60000; ++i) {  // decimal and scientific, every shape
    std::string s = signs[pick(3)];
    const std::size_t int_digits = pick(4) == 0 ? 0 : 1 + pick(pick(5) == 0 ? 40 : 20);
    const std::size_t frac_digits = pick(3) == 0 ? 0 : 1 + pick(pick(5) == 0 ? 40 : 20);
    s += digits(int_digits, false);
    if (frac_digits > 0 || pick(2) == 0) s += '.';
    s += digits(frac_digits, false);
    if (pick(3) != 0) {
      s += pick(2) ? 'e' : 'E';
      s += signs[pick(3)];
      const int range = pick(4) == 0 ? 400 : 340;
      s += std::to_string(pick(static_cast<std::uint64_t>(range)) + (pick(8) == 0 ? 0 : 0));
    }
    check(s);
  }
  for (int i = 0; i < 30000; ++i) {  // hexadecimal floats, with more digits than a double holds
    std::string s = signs[pick(3)];
    s += pick(2) ? "0x" : "0X";
    const std::size_t int_digits = pick(4) == 0 ? 0 : 1 + pick(16);
    const std::size_t frac_digits = pick(3) == 0 ? 0 : 1 + pick(20);
    s += digits(int_digits, true);
    if (frac_digits > 0 || pick(2) == 0) s += '.';
    s += digits(frac_digits, true);
    if (pick(4) != 0) {
      s += pick(2) ? 'p' : 'P';
      s += signs[pick(3)];
      s += std::to_string(pick(1200));
    }
    check(s);
  }
  for (int i = 0; i < 20000; ++i) {  // round trips of random doubles (normal and subnormal), %.17g and %a
    const std::uint64_t bits = rng() & (pick(4) == 0 ? 0x800FFFFFFFFFFFFFull : ~0ull);  // a quarter subnormal
    const double x = std::bit_cast<double>(bits);
    if (!std::isfinite(x)) continue;
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.17g", x);
    check(buf);
    std::snprintf(buf, sizeof buf, "%.25e", x);
    check(buf);
    std::snprintf(buf, sizeof buf, "%a", x);
    check(buf);
  }
  for (int i = 0; i < 10000; ++i) {  // exact halfway cases, and one unit in the 40th digit above and below
    const std::uint64_t bits = (rng() & 0x7FFFFFFFFFFFFFFFull) & (pick(4) == 0 ? 0x000FFFFFFFFFFFFFull : ~0ull);
    const double x = std::bit_cast<double>(bits);
    if (!std::isfinite(x) || x == std::numeric_limits<double>::max()) continue;
    const std::string mid = midpoint_text(x);  // "DIGITS" or "DIGITSe-K"
    check(mid);
    const std::size_t e = mid.find('e');
    const std::string mantissa = mid.substr(0, e), exponent = e == std::string::npos ? "" : mid.substr(e);
    check(mantissa + "00000000000000000000000000000000000001" + (exponent.empty() ? "e-38" : "e" + std::to_string(std::stol(exponent.substr(1)) - 38)));
    // just below: subtract one unit in the last place of a longer string (…999…)
    mpz_class m(mantissa);
    m = m * mpz_class("100000000000000000000000000000000000000") - 1;
    check(m.get_str() + (exponent.empty() ? "e-38" : "e" + std::to_string(std::stol(exponent.substr(1)) - 38)));
  }
  for (int i = 0; i < 2000; ++i) {  // very long digit strings (beyond any fast path)
    std::string s = "0." + std::string(pick(400), '0') + digits(200 + pick(600), false) + "e" + std::to_string(pick(700));
    check(s);
  }
  for (const char* special : {"inf", "INF", "infinity", "nan", "NAN", "nan(0x1)", "-inf", "+nan", "0x", ".", "e5", ".e5",
                              "1e", "0x1p+-3", "0x1.8p-+3", "1e+-5", "1e--5", "0x1p++3", "1e5e5", "0x1p3p3", "0x.p1", "0x1.p", "00x1", "0x0x1", "1_000", "١", "1\t", "1 ", "\t1"})
    check(special);
  std::printf("number reader: %zu strings agree with strtod\n", checked);
  EXPECT_GT(checked, 150000u);
}

// The contract reads to nearest whatever floating-point environment the caller left: strtod rounds in the
// current mode and from_chars' fast path multiplies in it. Hand-picked tokens whose reading depends on the
// mode (0.1 and 1e23 are inexact; 0x1.00000000000008p0 is a tie; 4e-324 and 2.5e-324 are subnormal, under
// FTZ/DAZ too), each read under every rounding mode and with FTZ and DAZ set, against the default reading;
// the caller's environment must come back unchanged.
TEST(NumberReader, ReadsToNearestInAnyEnvironment) {
  const char* tokens[] = {"0.1", "1e23", "-0.3", "0x1.00000000000008p0", "0x1.00000000000018p0", "4e-324", "2.5e-324",
                          "2.2250738585072011e-308", "1.7976931348623158e308", "123456789012345678901234567890"};
  std::vector<NumberParse> expected;
  for (const char* t : tokens) expected.push_back(parse_double(t));
  struct Mode {
    const char* name;
    int rounding;
    unsigned ftz_daz;  // MXCSR bits 15 (FTZ) and 6 (DAZ)
  };
  const Mode modes[] = {{"upward", FE_UPWARD, 0},          {"downward", FE_DOWNWARD, 0}, {"toward zero", FE_TOWARDZERO, 0},
                        {"FTZ+DAZ", FE_TONEAREST, 0x8040u}, {"upward, FTZ+DAZ", FE_UPWARD, 0x8040u}};
  for (const Mode& mode : modes) {
    std::fenv_t saved;
    std::fegetenv(&saved);
    std::fesetround(mode.rounding);
#if defined(__SSE2__)
    _mm_setcsr(_mm_getcsr() | mode.ftz_daz);
    const unsigned csr_before = _mm_getcsr();
#endif
    std::vector<NumberParse> got;
    for (const char* t : tokens) got.push_back(parse_double(t));
    const int rounding_after = std::fegetround();
#if defined(__SSE2__)
    const unsigned csr_after = _mm_getcsr();
#endif
    std::fesetenv(&saved);
    EXPECT_EQ(rounding_after, mode.rounding) << mode.name << ": the caller's rounding mode was not restored";
#if defined(__SSE2__)
    EXPECT_EQ(csr_after & ~0x3Fu, csr_before & ~0x3Fu) << mode.name << ": the caller's MXCSR modes were not restored";
#endif
    for (std::size_t i = 0; i < got.size(); ++i) {
      EXPECT_EQ(got[i].error, expected[i].error) << mode.name << ": " << tokens[i];
      EXPECT_EQ(std::bit_cast<std::uint64_t>(got[i].value), std::bit_cast<std::uint64_t>(expected[i].value))
          << mode.name << ": " << tokens[i];
    }
  }
}

TEST(NumberReader, IntegersInRange) {
  std::int64_t v = 0;
  EXPECT_TRUE(parse_integer("255", 0, 255, v) && v == 255);
  EXPECT_FALSE(parse_integer("256", 0, 255, v));
  EXPECT_TRUE(parse_integer("-128", -128, 127, v) && v == -128);
  EXPECT_TRUE(parse_integer("+7", 0, 10, v) && v == 7);
  EXPECT_FALSE(parse_integer("+-7", -10, 10, v));
  EXPECT_FALSE(parse_integer("1.0", 0, 10, v));
  EXPECT_FALSE(parse_integer("", 0, 10, v));
  EXPECT_FALSE(parse_integer("99999999999999999999", 0, INT64_MAX, v));
}

}  // namespace
}  // namespace raykernel::io
