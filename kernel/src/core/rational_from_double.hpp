// The exact value of a binary64 double as a GMP rational, decoded from its bits (sign, exponent,
// significand) without any floating-point operation, so that it is exact whatever the floating-point
// environment (mpq_set_d goes through FP arithmetic, which flush-to-zero modes corrupt). Finite x only.
//
// Used by the exact stage (exact_rational.cpp, where CGAL::Exact_rational is mpq_class) and the exact
// comparison (exact_compare.cpp); tests/nearest_hit_test.cpp checks it against mpq_class(double).
#pragma once

#include <gmpxx.h>

#include <bit>
#include <cstdint>

namespace raykernel::detail::exact {

[[nodiscard]] inline mpq_class rational_from_double(double x) {
  const auto bits = std::bit_cast<std::uint64_t>(x);
  const bool negative = (bits >> 63) != 0;
  const auto biased_exponent = static_cast<int>((bits >> 52) & 0x7ff);
  std::uint64_t significand = bits & ((std::uint64_t{1} << 52) - 1);
  int exponent = -1074;  // subnormal or zero
  if (biased_exponent != 0) {
    significand |= std::uint64_t{1} << 52;
    exponent = biased_exponent - 1075;
  }
  static_assert(sizeof(unsigned long) >= sizeof(std::uint64_t));
  mpq_class q{mpz_class{static_cast<unsigned long>(significand)}};
  if (exponent > 0)
    mpq_mul_2exp(q.get_mpq_t(), q.get_mpq_t(), static_cast<mp_bitcnt_t>(exponent));
  else
    mpq_div_2exp(q.get_mpq_t(), q.get_mpq_t(), static_cast<mp_bitcnt_t>(-exponent));
  if (negative) q = -q;
  return q;
}

}  // namespace raykernel::detail::exact
