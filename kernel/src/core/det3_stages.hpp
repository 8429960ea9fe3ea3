// Stages 1 and 2 of the certified ray–triangle cascade: the number types in which ray_triangle_formula.hpp is
// evaluated, and the decisions taken from them. Every value is a 3×3 determinant x·(y × z) of "leaves" (d, and
// the differences e_v = v − o); the types below make the formula's + − × compute, besides the value, what the
// error bound needs. Constants, derivations and valid ranges: core/error_bounds.hpp.
//
//   stage 1, filter:       FilterLeaf {v}: d, or ê = v ⊖ o (rounded once).
//                          FilterTerm {v, m}: a sum of products and its permanent m (Σ of |products|).
//   stage 2, compensated:  CompensatedLeaf {h, l}: d (l = 0), or TwoDiff(v, o) = (ê, exact error).
//                          CompensatedTerm {h, l, m}: a double-double h + l and the same m as stage 1.
//
// Stage 2's high parts and magnitudes are stage 1's values, operation for operation (h = P, c, t, s; m the
// same permanent), so one stage-2 evaluation serves both stages. Each type is templated on the lane type V
// (double for one value, Lanes4 for four values at once; lanes.hpp): every lane performs the scalar IEEE
// operations, which is what proofs/triangle/TriangleFilter.v and proofs/triangle/TriangleCompensated.v model.
//
// Twins: the same operations over IEEE binary64 (every bit pattern, ±0, inf and NaN included), compared bit for
// bit with this code by the differential runner (routines tri_filter, tri_relation_lanes, tri_compensated,
// tri_compensated_lanes; proofs/README.md), and tied to the models above:
//   proofs/triangle/TriangleTwins.v, `triangle_pi_filter_twin_sound`, `triangle_num_filter_twin_sound`
//   proofs/triangle/TriangleTwins.v, `triangle_den_filter_twin_sound`, `triangle_pi_lane_filter_twin_sound`
//   proofs/triangle/TriangleTwins.v, `triangle_pi_compensated_twin_sound`, `triangle_num_compensated_twin_sound`
//   proofs/triangle/TriangleTwins.v, `triangle_den_compensated_twin_sound`
//   proofs/triangle/TriangleTwins.v, `triangle_pi_lane_compensated_twin_sound`
//   proofs/triangle/TriangleTwins.v, `triangle_den_lane_compensated_twin_sound`
//   proofs/triangle/TriangleTwins.v, `triangle_num_lane_compensated_twin_sound`
//   proofs/triangle/TriangleTwins.v, `triangle_pi_lane_view_filter_twin_sound`
//   proofs/triangle/TriangleTwins.v, `triangle_num_lane_view_filter_twin_sound`
//   proofs/triangle/TriangleTwins.v, `triangle_den_lane_view_filter_twin_sound`
#pragma once

#include "core/absolute_terms.hpp"
#include "core/eft.hpp"
#include "core/enclosure.hpp"
#include "core/lanes.hpp"
#include "core/sign.hpp"
#include "core/error_bounds.hpp"

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>

namespace raykernel::detail {

// ---- Stage 1 ---------------------------------------------------------------------------------------------

template <class V>
struct FilterLeaf {
  V v;
};

template <class V>
struct FilterTerm {
  V v;  // the value as computed in binary64
  V m;  // its permanent as computed: Σ |x_i|·(|y_j ⊗ z_k| ⊕ |y_k ⊗ z_j|)
};

template <class V>
[[nodiscard]] [[gnu::always_inline]] inline FilterTerm<V> operator*(FilterLeaf<V> y, FilterLeaf<V> z) noexcept {
  const V p = y.v * z.v;
  return {p, abs(p)};
}
template <class V>
[[nodiscard]] [[gnu::always_inline]] inline FilterTerm<V> operator*(FilterLeaf<V> x, FilterTerm<V> c) noexcept {
  return {x.v * c.v, abs(x.v) * c.m};
}
template <class V>
[[nodiscard]] [[gnu::always_inline]] inline FilterTerm<V> operator+(FilterTerm<V> a, FilterTerm<V> b) noexcept {
  return {a.v + b.v, a.m + b.m};
}
template <class V>
[[nodiscard]] [[gnu::always_inline]] inline FilterTerm<V> operator-(FilterTerm<V> a, FilterTerm<V> b) noexcept {
  return {a.v - b.v, a.m + b.m};
}

// The dynamic absolute term A = (K_A ⊗ S) ⊕ U_A, S = (|x_0| ⊕ |x_1|) ⊕ |x_2|, of the determinants whose outer
// vector is x (d for the π's and den, ê_a for num): it covers products that underflow, whose error the outer
// product scales by |x_i| (error_bounds.hpp).
//
// Computed without arithmetic on subnormals: on x86 each operation with a subnormal result costs a microcode
// assist (about a hundred cycles; the default environment has no FTZ/DAZ), and so does one with a subnormal operand
// (K_A and U_A themselves); for S < 2^48 both K_A ⊗ S and the
// sum are subnormal. There K_A ⊗ S = RN(2^-1070·S) = 2^-1074·n, n = 16·S rounded to an integer, ties to even:
// 16·S ⊕ 2^52 = 2^52 + n exactly (16·S < 2^52), whose bit pattern is that of 2^52 plus n; adding U_A = 32·2^-1074
// is exact, and 2^-1074·k for an integer k < 2^53 has the bit pattern k. For S ≥ 2^48 (and NaN) the formula,
// evaluated on max(S, 2^48) so that no lane computes a subnormal. The same bits as the formula for every input:
// tests/triangle_stages_test.cpp (DetAbsoluteTerm) checks it against the formula bit for bit, and the twin runner's
// models compute the formula.
inline constexpr double absolute_term_subnormal_below = 0x1p48;  // K_A ⊗ S is subnormal below it (exact value)
inline constexpr double absolute_term_integer_shift = 0x1p52;     // x ⊕ 2^52 rounds x ∈ [0, 2^52) to an integer
inline constexpr double absolute_term_lift = 0x1p200;             // K_A·2^200, U_A·2^200 are normal (exact)
inline constexpr double absolute_term_drop = 0x1p-200;            // and scaled back (exact on normal values)
template <class V>
[[nodiscard]] [[gnu::always_inline]] inline V det3_absolute_term(V x0, V x1, V x2) noexcept {
  static_assert(bounds::triangle_absolute_scale == 0x1p-1070 && bounds::triangle_absolute == 0x1p-1069);
  const V s = (abs(x0) + abs(x1)) + abs(x2);
  const auto small = s < absolute_term_subnormal_below;
  // The formula 2^200 higher, then scaled back: K_A and U_A are subnormal, and an operation with a subnormal
  // operand costs an assist too. For S ≥ 2^48 every value is normal (K_A ⊗ S ≥ 2^-1022), so the scaling by
  // powers of two is exact and commutes with the rounding of the sum: the same bits (inf and NaN pass through).
  const V formula = ((bounds::triangle_absolute_scale * absolute_term_lift) *
                         select(small, V{} + absolute_term_subnormal_below, s) +
                     bounds::triangle_absolute * absolute_term_lift) *
                    absolute_term_drop;
  const V shifted = 16 * s + absolute_term_integer_shift;  // 2^52 + n where small
  const V subnormal = from_bits(to_bits(shifted) - (to_bits(absolute_term_integer_shift) - 32));
  return select(small, subnormal, formula);
}

// det3_filter: the sign of the exact determinant, from its stage-1 evaluation.
//   Error bound: |v − V| ≤ (C ⊗ m) ⊕ A, C = bounds::triangle_filter_{pi,num,den}_relative.
//   Valid range: all finite inputs; uncertain when m or A is not finite.
//   Certified by: proofs/triangle/TriangleFilter.v, `pi_filter_sound`, `num_filter_sound`, `den_filter_sound`.
// Branch-free, per lane: +1, −1, or uncertain (sign.hpp); never zero.
// (`relative` is a double, or per lane a V: the π's and num share one vector.)
template <class V, class Relative>
[[nodiscard]] [[gnu::always_inline]] inline IntegerOf<V> det3_filter_lanes(const FilterTerm<V>& r, Relative relative,
                                                                            V absolute) noexcept {
  const V bound = plus_absolute_term<V>(relative * r.m, absolute);  // ⊕ A (core/absolute_terms.hpp)
  return sign_lanes(r.v > bound, r.v < -bound);
}

// ---- Stage 2 ---------------------------------------------------------------------------------------------

template <class V>
struct CompensatedLeaf {
  V h, l;  // exactly the leaf's value h + l, |l| ≤ u|h|
};

template <class V>
struct CompensatedTerm {
  V h, l;  // the value approximated by h + l (error: error_bounds.hpp, "Ray–triangle", stage 2)
  V m;     // the permanent, as stage 1 computes it
};

// a·b for double-double a, b: P = a_h ⊗ b_h and the first-order low part by three FMAs (a_l·b_l dropped).
template <class V>
[[nodiscard]] [[gnu::always_inline]] inline V product_low_part(V ah, V al, V bh, V bl, V p) noexcept {
  return fma(ah, bl, fma(al, bh, fma(ah, bh, -p)));
}

template <class V>
[[nodiscard]] [[gnu::always_inline]] inline CompensatedTerm<V> operator*(CompensatedLeaf<V> y,
                                                                        CompensatedLeaf<V> z) noexcept {
  const V p = y.h * z.h;
  return {p, product_low_part(y.h, y.l, z.h, z.l, p), abs(p)};
}
template <class V>
[[nodiscard]] [[gnu::always_inline]] inline CompensatedTerm<V> operator*(CompensatedLeaf<V> x,
                                                                        CompensatedTerm<V> c) noexcept {
  const V p = x.h * c.h;
  return {p, product_low_part(x.h, x.l, c.h, c.l, p), abs(x.h) * c.m};
}
template <class V>
[[nodiscard]] [[gnu::always_inline]] inline CompensatedTerm<V> operator+(CompensatedTerm<V> a,
                                                                        CompensatedTerm<V> b) noexcept {
  const DD<V> s = two_sum(a.h, b.h);
  return {s.hi, (a.l + b.l) + s.lo, a.m + b.m};
}
template <class V>
[[nodiscard]] [[gnu::always_inline]] inline CompensatedTerm<V> operator-(CompensatedTerm<V> a,
                                                                        CompensatedTerm<V> b) noexcept {
  const DD<V> s = two_sum(a.h, -b.h);
  return {s.hi, (a.l - b.l) + s.lo, a.m + b.m};
}

// The stage-1 view of a stage-2 value (the same bits).
template <class V>
[[nodiscard]] [[gnu::always_inline]] inline FilterTerm<V> filter_view(const CompensatedTerm<V>& t) noexcept {
  return {t.h, t.m};
}

// det3_compensated: the enclosure |V − (h + l)| ≤ (K ⊗ m) ⊕ A of the exact determinant, K =
// bounds::triangle_compensated_relative (π, num) or triangle_compensated_den_relative (den).
//   Valid range: all finite inputs; the radius is +inf when h or l is not finite.
//   Certified by: proofs/triangle/TriangleCompensated.v, `pi_compensated_encloses`, `num_compensated_encloses`
//   Certified by: proofs/triangle/TriangleCompensated.v, `den_compensated_encloses`
template <class V>
[[nodiscard]] [[gnu::always_inline]] inline EnclosureT<V> det3_enclosure(const CompensatedTerm<V>& t, double relative,
                                                                         V absolute) noexcept {
  const V radius = plus_absolute_term<V>(relative * t.m, absolute);
  const MaskOf<V> finite = both(abs(t.h) <= bounds::largest_finite, abs(t.l) <= bounds::largest_finite);
  return {t.h, t.l, select(finite, radius, V{} + HUGE_VAL)};
}

}  // namespace raykernel::detail
