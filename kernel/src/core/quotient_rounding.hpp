// The correctly rounded quotient t = num/den from enclosures of num and den: one reciprocal of the
// denominator (shared by every quotient over the same den: prepare_divisor), one product, a residual by
// FMA and a correction, then a certified decision that the enclosure of t lies strictly inside the
// rounding interval of the candidate (so ties, which need the exact stage, are never decided here).
// Derivation and constants: error_bounds.hpp, "round_quotient". Cost per quotient: 1 TwoSum, 3 mul,
// 2 FMA, ~12 flops and the guards; per divisor: 1 TwoSum and 1 division.
#pragma once

#include "core/eft.hpp"
#include "core/enclosure.hpp"
#include "core/error_bounds.hpp"
#include "core/lanes.hpp"

#include <cstdint>
#include <optional>

namespace raykernel::detail {

// Half the distance from a normal double q to its nearer neighbour: 2^(e−53) for |q| ∈ [2^e, 2^(e+1)),
// 2^(e−54) when |q| = 2^e exactly (the gap below a power of two is half the gap above). Requires
// |q| ≥ bounds::half_gap_min_magnitude so that the result is normal. Per lane for vectors.
//   Certified by: proofs/plane/QuotientRounding.v, `half_gap_bits` (and the test proofs_half_gap).
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

// A denominator prepared for round_quotient: its enclosure renormalized, |den − (hi + lo)| ≤ radius with
// (hi, lo) = TwoSum of the enclosure's parts, the reciprocal 1 ⊘ hi, and the guard on |hi|.
template <class V>
struct DivisorT {
  V hi, lo, radius;
  V reciprocal;
  MaskOf<V> in_range;  // 2^-1000 ≤ |hi| ≤ 2^1000
};
using Divisor = DivisorT<double>;

template <class V>
[[nodiscard]] [[gnu::always_inline]] inline DivisorT<V> prepare_divisor(const EnclosureT<V>& den) noexcept {
  const DD<V> D = two_sum(den.hi, den.lo);
  const V abs_D = abs(D.hi);
  const MaskOf<V> in_range =
      both(abs_D >= bounds::divisor_min_magnitude, abs_D <= bounds::divisor_max_magnitude);
  // Out of range (0 included) the divisor is replaced by 1 before dividing: the decision is already
  // "uncertain", and the division must not raise divide-by-zero in a caller's trapping environment.
  const V one = broadcast<V>(1.0);
  return {D.hi, D.lo, den.radius, one / select(in_range, D.hi, one), in_range};
}

// The decision of round_quotient for one quotient (or one per lane): `certain` says whether t = RN(num/den)
// was certified.
template <class V>
struct QuotientRoundingT {
  V t;
  MaskOf<V> certain;
};
using QuotientRounding = QuotientRoundingT<double>;

// round_quotient: RN(num/den), ties to even, given |num − (n.hi + n.lo)| ≤ n.radius and the divisor
// prepared from an enclosure of den.
//   Error bound: |t − q| ≤ |w| + 2^-101·|q0| + (1 + 2^-9)·(E_n + |q0|·E_d)/|D| (error_bounds.hpp).
//   Valid range: |N| ≥ 2^-900, 2^-1000 ≤ |D| ≤ 2^1000, 2^-900 ≤ |q| ≤ largest_finite (checked: otherwise
//   not certain; NaN and ±inf fail every guard).
//   Certified by: proofs/plane/QuotientRounding.v, `round_quotient_sound` (the Coq definition computes every
//   guard and the test, as here, and returns (t, certain); per lane for vectors); on the bits, with
//   prepare_divisor and half_gap_to_nearer_neighbour, proofs/plane/PlaneQueryTwins.v, `round_quotient_twin_sound`.
template <class V>
[[nodiscard]] [[gnu::always_inline]] inline QuotientRoundingT<V> round_quotient(const EnclosureT<V>& num,
                                                                                const DivisorT<V>& den) noexcept {
  using namespace bounds;
  const DD<V> N = two_sum(num.hi, num.lo);
  const V q0 = N.hi * den.reciprocal;
  const V r1 = fma(-q0, den.hi, N.hi);  // RN(N − q0·D)
  const V r2 = fma(-q0, den.lo, N.lo);  // RN(n − q0·d)
  const V c = (r1 + r2) * den.reciprocal;
  const V q = q0 + c;
  const V w = c - (q - q0);  // Fast2Sum: q + w = q0 + c exactly, as |c| ≤ |q0|
  const V abs_q0 = abs(q0);
  const V abs_D = abs(den.hi);
  const V abs_q = abs(q);
  const MaskOf<V> in_range = both(both(abs(N.hi) >= quotient_min_magnitude, den.in_range),
                                  both(abs_q >= quotient_min_magnitude, abs_q <= largest_finite));
  const V x = ((abs_q0 * den.radius) + num.radius) * quotient_enclosure_factor;
  const V y = ((abs_q0 * quotient_relative) + abs(w)) * abs_D;
  // Where a guard fails (a zero numerator among them) the test does not count, and its operands are taken
  // from q = 1 instead of q: the half gap of 0 or of a subnormal q is no normal number, and its product with
  // |D| would overflow (raising the flag, at the cost of an assist, and clearing it on the way out: fp_environment.hpp).
  // The same answers: `certain` is false there either way.
  const V h = half_gap_to_nearer_neighbour(select(in_range, q, broadcast<V>(1.0)));
  return {q, both(in_range, (x + y) * quotient_test_factor < h * abs_D)};
}

// The same decision as an optional: t, or nothing when not certain.
[[nodiscard]] inline std::optional<double> round_quotient_if_certain(const Enclosure& num, const Divisor& den) noexcept {
  const QuotientRounding r = round_quotient(num, den);
  if (!r.certain) return std::nullopt;
  return r.t;
}

}  // namespace raykernel::detail
