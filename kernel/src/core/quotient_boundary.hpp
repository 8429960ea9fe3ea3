// The correctly rounded quotient t = num/den decided at its rounding boundaries, exactly: for the quotients
// round_quotient cannot certify because t lies on a boundary or closer to it than any enclosure can tell — a
// rounding tie, t exactly halfway between two doubles (a triangle seen straight down at dyadic coordinates: t in
// [8, 9) with a denominator 2^50 is a tie one time in two) — without rational arithmetic.
//
// Given a candidate q (the rounding of an enclosure of t, which is t's rounding or one of its neighbours), RN(t)
// is q exactly when t lies strictly between the midpoints m⁻ = (q⁻ + q)/2 and m⁺ = (q + q⁺)/2 of q and its
// neighbours q⁻ < q < q⁺; on m⁺ (or m⁻) it is the one of q, q⁺ (q⁻, q) whose last significand bit is 0 (ties to
// even). The side of t against a midpoint m = (x + y)/2 is
//
//     sign(t − m) = sign(2·num − (x + y)·den)·sign(den),
//
// the comparison of the two quotients num/den and (x + y)/2 — compare_quotients_expansion on num, den and the
// expansions TwoSum(x, y) (exactly x + y) and {2}, exact (core/expansion_compare.hpp). Nothing is rounded: no
// error constant.
//   Valid range: 2^-968 ≤ |q| < largest_finite (so that q⁻ and q⁺ are normal doubles of q's sign and the
//   products exact unless the builder says otherwise), num and den as exact expansions of at most 16 components
//   each; nothing (the exact stage decides) when a product is not exact, the candidate is not t's rounding or
//   its neighbour's (t beyond m⁺ or below m⁻), q is outside that range, or q + q⁺ overflows (the top binade).
//   Certified by: proofs/core/QuotientBoundary.v, `round_quotient_at_boundaries_sound` (a value is finite and
//   RN(Σnum/Σden) for den_sign the sign of Σden, ±1, and at most 16 components each), from `side_of_midpoint_sound`
//   (a certain side is the sign of t − (x + y)/2: proofs/core/Expansions.v, `compare_quotients_expansion_sound`)
//   and proofs/core/MidpointRounding.v, `boundary_decision_correct` (the choice of RN(t) from the two sides:
//   `rn_between_midpoints`, `rn_at_midpoint_above`, `rn_at_midpoint_below`; ties to even by the parity of the
//   significand field, `b754_canonical`). Liveness: ties and the values between the midpoints are decided
//   (`round_quotient_at_boundaries_tie_even`, `round_quotient_at_boundaries_tie_odd`,
//   `round_quotient_at_boundaries_between`). The twin runs against this code in the differential runner (routine
//   quotient_boundary).
#pragma once

#include "core/eft.hpp"
#include "core/error_bounds.hpp"
#include "core/expansion.hpp"
#include "core/neighbours.hpp"
#include "core/sign.hpp"
#include "core/expansion_compare.hpp"

#include <bit>
#include <cmath>
#include <cstdint>
#include <optional>

namespace raykernel::detail {

namespace boundary_internal {

// The sign of t − (x + y)/2 for t = num/den (den's exact sign given, ±1), or uncertain.
template <std::size_t A, std::size_t B>
[[nodiscard]] inline Sign side_of_midpoint(const Expansion<A>& num, const Expansion<B>& den, int den_sign, double x,
                                           double y) noexcept {
  // (Capacities of 16, as the triangles' comparisons: one instantiation of compare_quotients_expansion.)
  // {x, y} as the expansion TwoSum(x, y) = (s, e): nonoverlapping, so that the checked sign of the difference
  // decides, and s + e = x + y exactly.
  const DoubleDouble s = two_sum(x, y);
  if (!std::isfinite(s.lo)) return Sign::uncertain;  // x + y overflowed (q in the top binade)
  Expansion<16> pair;
  ExpansionBuilder::from_pair(s, pair);
  Expansion<16> two;
  two.component[0] = 2;
  two.size = 1;
  const Sign delta = compare_quotients_expansion(num, den, pair, two);  // sign(num·2 − (x + y)·den)
  if (!is_certain(delta)) return Sign::uncertain;
  return static_cast<Sign>(static_cast<int>(delta) * den_sign);
}

[[nodiscard]] inline bool even(double x) noexcept { return (std::bit_cast<std::uint64_t>(x) & 1) == 0; }

}  // namespace boundary_internal

// RN(t) for the candidate q from `side(x, y)`, the sign of t − (x + y)/2 (or uncertain), for any exact value t:
// the one decision of the quotients below and of the sphere's roots (sphere/ray_sphere_stages.hpp). Nothing when
// the sides do not decide, q is outside [2^-968, largest_finite), or q is not RN(t).
//   Certified by: proofs/core/MidpointRounding.v, `boundary_decision_correct` (the choice of RN(t) from the two
//   sides), for the quotients through `round_quotient_at_boundaries_sound` (proofs/core/QuotientBoundary.v).
template <class Side>
[[nodiscard]] inline std::optional<double> round_at_midpoints(const Side& side, double q) noexcept {
  const double magnitude = std::fabs(q);
  if (!(magnitude >= bounds::half_gap_min_magnitude && magnitude < bounds::largest_finite)) return std::nullopt;
  const double up = next_up(q), down = next_down(q);
  const Sign above = side(q, up);  // t against m⁺
  if (above == Sign::zero) return boundary_internal::even(q) ? q : up;
  if (above != Sign::negative) return std::nullopt;  // t > m⁺ (or undecided): q is not RN(t)
  const Sign below = side(down, q);  // t against m⁻
  if (below == Sign::zero) return boundary_internal::even(q) ? q : down;
  if (below != Sign::positive) return std::nullopt;
  return q;
}

// round_at_midpoints for q, then for next_up(q), then for next_down(q): RN(t) when q is t's
// rounding or one of its neighbours.
template <class Side>
[[nodiscard]] inline std::optional<double> round_near_midpoints(const Side& side, double q) noexcept {
  if (const std::optional<double> r = round_at_midpoints(side, q)) return r;
  if (const std::optional<double> r = round_at_midpoints(side, next_up(q))) return r;
  return round_at_midpoints(side, next_down(q));
}

// RN(t) from a candidate q a few doubles off: the decision of round_at_midpoints at q, moving to q's neighbour on
// the side t lies on (t > m⁺: up; t < m⁻: down) at most `steps` times. Each answer is round_at_midpoints' at the
// q it stops at, so certified as that one; the walk only chooses where to look.
template <class Side>
[[nodiscard]] [[gnu::always_inline]] inline std::optional<double> round_walking_to_midpoints(const Side& side, double q, int steps) noexcept {
  for (int step = 0; step <= steps; ++step) {
    const double magnitude = std::fabs(q);
    if (!(magnitude >= bounds::half_gap_min_magnitude && magnitude < bounds::largest_finite)) return std::nullopt;
    const double up = next_up(q), down = next_down(q);
    const Sign above = side(q, up);
    if (above == Sign::zero) return boundary_internal::even(q) ? q : up;
    if (above == Sign::positive) {
      q = up;
      continue;
    }
    if (above != Sign::negative) return std::nullopt;
    const Sign below = side(down, q);
    if (below == Sign::zero) return boundary_internal::even(q) ? q : down;
    if (below == Sign::negative) {
      q = down;
      continue;
    }
    if (below != Sign::positive) return std::nullopt;
    return q;
  }
  return std::nullopt;
}

// RN(num/den), ties to even, for the candidate q; nothing when the signs do not decide (see above).
template <std::size_t A, std::size_t B>
[[nodiscard]] inline std::optional<double> round_quotient_at_boundaries(const Expansion<A>& num,
                                                                         const Expansion<B>& den, int den_sign,
                                                                         double q) noexcept {
  return round_at_midpoints(
      [&](double x, double y) { return boundary_internal::side_of_midpoint(num, den, den_sign, x, y); }, q);
}

// RN(num/den) from the candidate q or, when q is one ulp off (a stage's enclosure rounded to t's neighbour: a t
// just past a midpoint), from either neighbour of q: round_quotient_at_boundaries for q, then for
// next_up(q), then for next_down(q). Each value is certified on its own.
//   Certified by: proofs/core/QuotientBoundary.v, `round_quotient_near_sound` (from
//   `round_quotient_at_boundaries_sound` for each of the three candidates).
template <std::size_t A, std::size_t B>
[[nodiscard]] inline std::optional<double> round_quotient_near(const Expansion<A>& num, const Expansion<B>& den,
                                                                int den_sign, double q) noexcept {
  return round_near_midpoints(
      [&](double x, double y) { return boundary_internal::side_of_midpoint(num, den, den_sign, x, y); }, q);
}

}  // namespace raykernel::detail
