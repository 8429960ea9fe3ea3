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
#include "certified/lanes.hpp"

#include <bit>
#include <cmath>
#include <cstdint>
#include <optional>

namespace raykernel::detail {

// Half the distance from a normal double q to its nearer neighbour: 2^(e−53) for |q| ∈ [2^e, 2^(e+1)),
// 2^(e−54) when |q| = 2^e exactly (the gap below a power of two is half the gap above). Requires
// |q| ≥ 2^-968 so that the result is normal. Per lane for Lanes8.
template <class V>
[[nodiscard]] [[gnu::always_inline]] inline V half_gap_to_nearer_neighbour(V q) noexcept {
  using Bits = BitsOf<V>;
  constexpr std::uint64_t fraction_mask = (std::uint64_t{1} << 52) - 1;
  const Bits bits = to_bits(abs(q));
  const Bits biased_exponent = bits >> 52;
  // 53, or 54 where the fraction is zero (to_integer turns the comparison into 1/0).
  const Bits shift = (Bits{} + 53) + (Bits)(to_integer((bits & fraction_mask) == 0));  // NOLINT: vector cast
  return from_bits((biased_exponent - shift) << 52);
}

// The decision of round_quotient for one query (or one per lane): `certain` says whether t = RN(num/den)
// was certified.
template <class V>
struct QuotientRoundingT {
  V t;
  MaskOf<V> certain;
};
using QuotientRounding = QuotientRoundingT<double>;

// round_quotient_decision: RN(num/den), ties to even, given |num − (n.hi + n.lo)| ≤ n.radius and
// |den − (d.hi + d.lo)| ≤ d.radius with num ≠ 0 and den ≠ 0.
//   Valid range: |N|, |D|, |q0| ≥ 2^-900 and q finite (checked; otherwise not certain).
//   Certified by: proofs/RoundQuotient.v, `round_quotient_decision_sound` (the Coq definition computes every
//   guard and the test, as here, and returns (t, certain); per lane for Lanes8).
template <class V>
[[nodiscard]] [[gnu::always_inline]] inline QuotientRoundingT<V> round_quotient_decision(const EnclosureT<V>& n,
                                                                                         const EnclosureT<V>& d) noexcept {
  using namespace bounds;
  const DD<V> N = two_sum(n.hi, n.lo);
  const DD<V> D = two_sum(d.hi, d.lo);
  const V q0 = N.hi / D.hi;
  const V abs_q0 = abs(q0);
  const V abs_D = abs(D.hi);
  const V abs_N = abs(N.hi);
  // The guards also reject NaN and ±inf (comparisons are false), and radii that are not finite.
  const MaskOf<V> in_range =
      both(both(both(abs_N >= quotient_min_magnitude, abs_D >= quotient_min_magnitude),
                both(abs_q0 >= quotient_min_magnitude, abs_N < HUGE_VAL)),
           both(both(abs_D < HUGE_VAL, abs_q0 < HUGE_VAL), both(n.radius < HUGE_VAL, d.radius < HUGE_VAL)));

  const V r1 = fma(-q0, D.hi, N.hi);  // RN(N − q0·D), exact in practice (division remainder)
  const V r2 = fma(-q0, D.lo, N.lo);  // RN(n − q0·d)
  const V c = (r1 + r2) / D.hi;
  const DD<V> q = two_sum(q0, c);

  const V x = ((abs_q0 * d.radius) + n.radius) * quotient_enclosure_factor;
  const V y = ((abs_q0 * quotient_relative) + abs(q.lo)) * abs_D;
  const V h = half_gap_to_nearer_neighbour(q.hi);
  const MaskOf<V> inside = (x + y) * quotient_test_factor < h * abs_D;
  return {q.hi, both(both(in_range, abs(q.hi) < HUGE_VAL), inside)};
}

// round_quotient: the same decision as an optional: t, or nullopt when not certain.
//   Certified by: proofs/RoundQuotient.v, `round_quotient_sound` (a corollary of the above).
[[nodiscard]] inline std::optional<double> round_quotient(const Enclosure& n, const Enclosure& d) noexcept {
  const QuotientRounding r = round_quotient_decision(n, d);
  if (!r.certain) return std::nullopt;
  return r.t;
}

}  // namespace raykernel::detail
