// Exact arithmetic for the harnesses' own oracles: doubles as GMP rationals, and an independent check that a
// double is a rational rounded to nearest as docs/contract.md §1 says. Header-only; a harness that includes it links
// raykernel_dep::gmpxx. Nothing here calls the kernel, so the oracles share no code with it.
#pragma once

#include <gmpxx.h>

#include <cfloat>
#include <cmath>

#include "fuzz_support.hpp"

namespace raykernel::fuzz {

// The exact value of a finite double (mpq_set_d is exact).
[[nodiscard]] inline mpq_class exact_of(double x) { return mpq_class(x); }

// 2^e, exactly.
[[nodiscard]] inline mpq_class power_of_two(int e) {
  mpq_class q(1);
  if (e >= 0)
    q.get_num() <<= static_cast<mp_bitcnt_t>(e);
  else
    q.get_den() <<= static_cast<mp_bitcnt_t>(-e);
  return q;
}

// Whether r is q rounded to nearest binary64, ties to even, with gradual underflow, overflow to ±inf and the
// sign kept when a nonzero q rounds to zero (docs/contract.md §1). Verified, not recomputed: q must lie in r's
// rounding interval, whose ends (the midpoints to r's neighbours) belong to it only when r's significand is
// even. Above DBL_MAX the neighbour is 2^1024 (IEEE 754 §4.3.1: overflow at 2^1024 − 2^970 and beyond).
[[nodiscard]] inline bool is_round_to_nearest_even(const mpq_class& q, double r) {
  if (std::isnan(r)) return false;
  const int s = sgn(q);
  if (s == 0) return bits(r) == 0;  // +0
  if (std::signbit(r) != (s < 0)) return false;
  const mpq_class a = abs(q);
  const double m = std::fabs(r);
  if (std::isinf(m)) return a >= power_of_two(1024) - power_of_two(970);
  const mpq_class mq = exact_of(m);
  const mpq_class up = m == DBL_MAX ? power_of_two(1024) : exact_of(std::nextafter(m, HUGE_VAL));
  const mpq_class hi_edge = (mq + up) / 2;
  const mpq_class lo_edge = m == 0 ? mpq_class(0) : (mq + exact_of(std::nextafter(m, 0.0))) / 2;
  const bool even = (bits(m) & 1) == 0;
  if (a > hi_edge || a < lo_edge) return false;
  if ((a == hi_edge || a == lo_edge) && !even) return false;
  return true;
}

}  // namespace raykernel::fuzz
