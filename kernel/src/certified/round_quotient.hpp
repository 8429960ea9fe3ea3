// The correctly rounded quotient t = num/den from enclosures of num and den, or `nullopt` when the
// enclosures are too wide to decide (t within about rad of a rounding boundary, including exact ties,
// which need the exact stage), or when a guard excludes the input range.
//
// The candidate is a double-double quotient q0 + c (one Newton-like correction of q0 = N ⊘ D by the
// residual N − q0·D computed with FMAs); q = RN(q0 + c) is returned only when the certified enclosure of t
// around q0 + c lies strictly inside q's rounding interval. Derivation and constants: error_bounds.hpp,
// "round_quotient". Cost: 2 TwoSum, 2 div, 3 FMA, ~10 flops.
#pragma once

#include "certified/eft.hpp"
#include "certified/enclosure.hpp"
#include "certified/error_bounds.hpp"

#include <bit>
#include <cmath>
#include <cstdint>
#include <optional>

namespace raykernel::detail {

// Half the distance from a normal double q to its nearer neighbour: 2^(e−53) for |q| ∈ [2^e, 2^(e+1)),
// 2^(e−54) when |q| = 2^e exactly (the gap below a power of two is half the gap above). Requires
// |q| ≥ 2^-968 so that the result is normal.
[[nodiscard]] inline double half_gap_to_nearer_neighbour(double q) noexcept {
  constexpr std::uint64_t fraction_mask = (std::uint64_t{1} << 52) - 1;
  const std::uint64_t bits = std::bit_cast<std::uint64_t>(std::fabs(q));
  const std::uint64_t biased_exponent = bits >> 52;
  const std::uint64_t shift = (bits & fraction_mask) == 0 ? 54 : 53;
  return std::bit_cast<double>((biased_exponent - shift) << 52);
}

// round_quotient: RN(num/den), ties to even, given |num − (n.hi + n.lo)| ≤ n.radius and
// |den − (d.hi + d.lo)| ≤ d.radius with num ≠ 0 and den ≠ 0.
//   Valid range: |N|, |D|, |q0| ≥ 2^-900 and q finite (checked; otherwise nullopt).
//   Certified by: proofs/RoundQuotient.v, `round_quotient_sound`.
[[nodiscard]] inline std::optional<double> round_quotient(const Enclosure& n, const Enclosure& d) noexcept {
  using namespace bounds;
  const DoubleDouble N = two_sum(n.hi, n.lo);
  const DoubleDouble D = two_sum(d.hi, d.lo);
  const double q0 = N.hi / D.hi;
  // The guards also reject NaN and ±inf (comparisons are false), and radii that are not finite.
  if (!(std::fabs(N.hi) >= quotient_min_magnitude && std::fabs(D.hi) >= quotient_min_magnitude &&
        std::fabs(q0) >= quotient_min_magnitude && std::isfinite(N.hi) && std::isfinite(D.hi) &&
        std::isfinite(q0) && n.radius < HUGE_VAL && d.radius < HUGE_VAL))
    return std::nullopt;

  const double r1 = std::fma(-q0, D.hi, N.hi);  // RN(N − q0·D), exact in practice (division remainder)
  const double r2 = std::fma(-q0, D.lo, N.lo);  // RN(n − q0·d)
  const double c = (r1 + r2) / D.hi;
  const DoubleDouble q = two_sum(q0, c);
  if (!std::isfinite(q.hi)) return std::nullopt;

  const double abs_q0 = std::fabs(q0);
  const double abs_D = std::fabs(D.hi);
  const double x = ((abs_q0 * d.radius) + n.radius) * quotient_enclosure_factor;
  const double y = ((abs_q0 * quotient_relative) + std::fabs(q.lo)) * abs_D;
  const double h = half_gap_to_nearer_neighbour(q.hi);
  if ((x + y) * quotient_test_factor < h * abs_D) return q.hi;
  return std::nullopt;
}

}  // namespace raykernel::detail
