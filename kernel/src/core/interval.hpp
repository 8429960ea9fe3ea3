// Interval arithmetic in round-to-nearest: each binary64 operation rounded to nearest, then widened by one ulp
// outwards. A filter for constructions whose error analysis is not written per formula (the closest point,
// closest/closest_formula.hpp): each interval holds the exact value of the expression it was computed from.
//
// Error bound: RN(x) is within half an ulp of x, and the neighbour of RN(x) away from x is at least that far from
// it, so x ∈ [next_down(RN(x)), next_up(RN(x))] — with gradual underflow (the absolute error of RN is at most
// 2^-1075, below the smallest step 2^-1074) and with overflow (RN(x) = +inf gives next_down = DBL_MAX ≤ x, and
// next_up(+inf) = +inf). Interval operations take the exact operation's extreme values at the endpoints (for a
// product, 0 · ±inf counts as 0, the product's limit; an endpoint ±inf stands for "beyond the doubles").
// Valid range: operands whose ends are finite doubles; every operation and widening may overflow (a lower end
// −inf, an upper end +inf, read as extended reals). Operands with an infinite end (the output of an overflow fed
// to the next operation) are argued above, not proved: a lower end is never +inf nor an upper end −inf, so sums
// and differences of ends never form inf − inf, and a product's 0 · ±inf is replaced by its limit 0.
// Certified by: proofs/core/IntervalWidening.v — `widen_encloses`; on IEEE doubles with overflow `ieee_add_encloses`,
// `ieee_sub_encloses`, `ieee_neg_encloses`, `ieee_mul_encloses`, `ieee_square_encloses`, `ieee_div_encloses`,
// `ieee_sign_sound` (next_up is Flocq's Bsucc: checked bit for bit against std::nextafter by
// tests/closest_point_test.cpp, not proved). Assumes the default floating-point environment (round to nearest, no
// FTZ or DAZ; FpEnvironmentScope, core/fp_environment.hpp, installs it).
#pragma once

#include "core/neighbours.hpp"

#include <algorithm>
#include <limits>

namespace raykernel::detail {

struct Interval {
  double lo, hi;  // lo ≤ exact ≤ hi

  static Interval point(double x) noexcept { return {x, x}; }
};

[[nodiscard]] inline Interval operator+(const Interval& a, const Interval& b) noexcept {
  return {next_down(a.lo + b.lo), next_up(a.hi + b.hi)};
}
[[nodiscard]] inline Interval operator-(const Interval& a, const Interval& b) noexcept {
  return {next_down(a.lo - b.hi), next_up(a.hi - b.lo)};
}
[[nodiscard]] inline Interval operator-(const Interval& a) noexcept { return {-a.hi, -a.lo}; }

namespace interval_detail {
[[nodiscard]] inline double product(double x, double y) noexcept {
  const double p = x * y;
  return p == p ? p : 0.0;  // NaN only from 0 · ±inf: the product's limit is 0
}
}  // namespace interval_detail

[[nodiscard]] inline Interval operator*(const Interval& a, const Interval& b) noexcept {
  using interval_detail::product;
  const double p1 = product(a.lo, b.lo), p2 = product(a.lo, b.hi), p3 = product(a.hi, b.lo),
               p4 = product(a.hi, b.hi);
  return {next_down(std::min(std::min(p1, p2), std::min(p3, p4))),
          next_up(std::max(std::max(p1, p2), std::max(p3, p4)))};
}

// x² (never below 0).
[[nodiscard]] inline Interval square(const Interval& a) noexcept {
  const double l = a.lo * a.lo, h = a.hi * a.hi;
  if (a.lo <= 0 && a.hi >= 0) return {0.0, next_up(std::max(l, h))};
  return {std::max(0.0, next_down(std::min(l, h))), next_up(std::max(l, h))};
}

// a / b for a ≥ 0 and b.lo > 0 (the caller checks b.lo > 0).
[[nodiscard]] inline Interval divide_nonnegative(const Interval& a, const Interval& b) noexcept {
  return {std::max(0.0, next_down(std::max(a.lo, 0.0) / b.hi)), next_up(a.hi / b.lo)};
}

// The sign of every value in the interval: +1, −1, or 0 when it is the point 0; `uncertain` (2) otherwise.
inline constexpr int interval_uncertain = 2;
[[nodiscard]] inline int interval_sign(const Interval& a) noexcept {
  if (a.lo > 0) return 1;
  if (a.hi < 0) return -1;
  if (a.lo == 0 && a.hi == 0) return 0;
  return interval_uncertain;
}

}  // namespace raykernel::detail
