// The certified order of two ray parameters t_1 = N_1/D_1 and t_2 = N_2/D_2 (num and den of two planes
// along one ray), for nearest_hit. Since D_1, D_2 ≠ 0,
//
//     sign(t_1 − t_2) = sign(Δ)·sign(D_1)·sign(D_2),        Δ = N_1·D_2 − N_2·D_1,
//
// and Δ, a degree-2 polynomial in the four values, is decided by the same cascade as the relation, from
// the same per-plane stage results (plane/ray_plane_stages.hpp):
//
//   stage 1  compare_quotients_filter        binary64 from the stage-1 values and their error bounds
//   stage 2  compare_quotients_compensated   double-double from the stage-2 enclosures
//   stage 3  compare_quotients_expansion     exact, from the stage-3 expansions (core/expansion_compare.hpp)
//   stage 4  exact::compare_quotients        exact rationals (plane/exact_plane_compare.hpp)
//
// Rounded t values are never compared: two planes whose t round to the same double are still ordered, and
// Δ = 0 (an exact tie) is certified only by an exact stage. Constants and derivations:
// core/error_bounds.hpp, "Comparing two quotients".
#pragma once

#include "core/absolute_terms.hpp"
#include "core/dot3_filter.hpp"
#include "core/eft.hpp"
#include "core/enclosure.hpp"
#include "core/error_bounds.hpp"
#include "core/expansion.hpp"
#include "core/expansion_compare.hpp"
#include "core/sign.hpp"
#include "plane/ray_plane_cascade.hpp"

#include <cmath>
#include <cstddef>

namespace raykernel::detail {

// A real V known through one double: |V − value| ≤ radius (per lane when L is a lane type: nearest_hit
// tests four or eight planes' t against the best so far at once, nearest/nearest_screen.hpp).
template <class L>
struct RoundedEnclosureT {
  L value;
  L radius;
};
using RoundedEnclosure = RoundedEnclosureT<double>;

// The stage-1 enclosure of a dot product: value s and the bound (C ⊗ m) ⊕ 3μ that dot3_filter compares s
// against (the same operations, in the same order). |s − V| ≤ that bound is, for den and for num,
// proofs/plane/PlaneFilter.v's `den_filter_encloses` and `num_filter_encloses` (both by `dot3_filter_bound_encloses`).
template <class L>
[[nodiscard]] [[gnu::always_inline]] inline RoundedEnclosureT<L> filter_enclosure(const Dot3RoundedT<L>& r,
                                                                                  double relative_constant) noexcept {
  return {r.value, dot3_filter_bound(r, relative_constant)};
}

// R = ((|x_1| ⊗ f_2) ⊕ (e_1 ⊗ (|y_2| ⊕ f_2))) ⊕ ((|x_2| ⊗ f_1) ⊕ (e_2 ⊗ (|y_1| ⊕ f_1))): a computed bound, up
// to the factor C_p and the absolute term, on the error that the input radii e_i (of N_i ≈ x_i) and f_i
// (of D_i ≈ y_i) propagate into N_1·D_2 − N_2·D_1 (error_bounds.hpp: R ≥ ρ/(1+u)^4 − 4η/(1+u)^2).
template <class L>
[[nodiscard]] [[gnu::always_inline]] inline L compare_propagated_error(L x1, L e1, L y1, L f1, L x2, L e2, L y2,
                                                                       L f2) noexcept {
  return (abs(x1) * f2 + e1 * (abs(y2) + f2)) + (abs(x2) * f1 + e2 * (abs(y1) + f1));
}

// compare_quotients_filter: the sign of Δ = N_1·D_2 − N_2·D_1 from one-double enclosures of the four values.
//   Formula:     P = x_1 ⊗ y_2, Q = x_2 ⊗ y_1, δ = P ⊖ Q, M = |P| ⊕ |Q|,
//                B = ((C_f ⊗ M) ⊕ (C_p ⊗ R)) ⊕ U_c;  δ > B ⇒ Δ > 0, δ < −B ⇒ Δ < 0.
//   Error bound: |Δ − δ| ≤ ρ + 2u(|P| + |Q|) + 2η ≤ B, with C_f = (2 + 16u)u, C_p = 1 + 16u, U_c = 8μ.
//   Valid range: all finite inputs with radii ≥ 0; uncertain (never wrong) when anything overflows.
//   Certified by: proofs/compare/CompareQuotients.v, `compare_quotients_filter_sound`.
// Cost: 8 mul, 9 add, 6 abs (δ and M: 2 mul, 2 add; R: 4 mul, 5 add; B: 2 mul, 2 add).
// compare_quotients_filter_lanes gives the sign as an integer (Sign's values) per lane, for one pair
// (L = double) or for four or eight first quotients against one second (L = Lanes4, Lanes8: each lane is
// the scalar routine's operations on that lane's values, lanes.hpp). Neither comparison holds when the bound
// or δ is NaN or infinite (an overflow): uncertain.
template <class L>
[[nodiscard]] [[gnu::always_inline]] inline IntegerOf<L> compare_quotients_filter_lanes(
    const RoundedEnclosureT<L>& n1, const RoundedEnclosureT<L>& d1, const RoundedEnclosureT<L>& n2,
    const RoundedEnclosureT<L>& d2) noexcept {
  using namespace bounds;
  const L p = n1.value * d2.value;  // P = x_1 ⊗ y_2
  const L q = n2.value * d1.value;  // Q = x_2 ⊗ y_1
  const L delta = p - q;            // δ = P ⊖ Q
  const L magnitude = abs(p) + abs(q);
  const L propagated =
      compare_propagated_error(n1.value, n1.radius, d1.value, d1.radius, n2.value, n2.radius, d2.value, d2.radius);
  const L bound = plus_absolute(compare_filter_relative * magnitude + compare_propagation_factor * propagated,
                                absolute_constant(compare_absolute));
  // Both comparisons can hold only for a negative bound (negative radii, which no stage produces): then
  // positive, as the test δ > B comes first (as in the twin of proofs/compare/CompareTwins.v).
  const auto above = delta > bound;
  return sign_lanes(above, (delta < -bound) & (above == 0));
}

[[nodiscard]] inline Sign compare_quotients_filter(const RoundedEnclosure& n1, const RoundedEnclosure& d1,
                                                   const RoundedEnclosure& n2, const RoundedEnclosure& d2) noexcept {
  return static_cast<Sign>(compare_quotients_filter_lanes(n1, d1, n2, d2));
}

// compare_quotients_compensated: an enclosure of Δ = N_1·D_2 − N_2·D_1 from double-double enclosures of the
// four values (the stage-2 enclosures of num and den); its sign is then decided by enclosure_sign.
//   Formula:     (a_i, α_i) = TwoSum(N_i.hi, N_i.lo), (b_i, β_i) = TwoSum(D_i.hi, D_i.lo),
//                (P, p) = TwoProduct(a_1, b_2), (Q, q) = TwoProduct(a_2, b_1),
//                c_1 = fma(a_1, β_2, α_1 ⊗ b_2), c_2 = fma(a_2, β_1, α_2 ⊗ b_1), (S, s) = TwoSum(P, −Q),
//                hi = S, lo = ((p ⊖ q) ⊕ (c_1 ⊖ c_2)) ⊕ s, E = ((K_c ⊗ M) ⊕ (C_p ⊗ R)) ⊕ U_c, M = |P| ⊕ |Q|.
//   Error bound: |Δ − (hi + lo)| ≤ (1+u)ρ + 16.02u²(|P| + |Q|) + 6.02η ≤ E, K_c = 2^-101 (error_bounds.hpp).
//   Valid range: all finite inputs; the radius is +inf or NaN (no information) when a value overflows.
//   Certified by: proofs/compare/CompareQuotients.v, `compare_quotients_compensated_enclosure`, then
//   `enclosure_sign_sound` for the sign.
[[nodiscard]] inline Enclosure compare_quotients_compensated(const Enclosure& n1, const Enclosure& d1,
                                                             const Enclosure& n2, const Enclosure& d2) noexcept {
  using namespace bounds;
  const DoubleDouble a1 = two_sum(n1.hi, n1.lo);  // a_1 + α_1 = N_1.hi + N_1.lo, |α_1| ≤ u|a_1|
  const DoubleDouble b1 = two_sum(d1.hi, d1.lo);
  const DoubleDouble a2 = two_sum(n2.hi, n2.lo);
  const DoubleDouble b2 = two_sum(d2.hi, d2.lo);
  const DoubleDouble p = two_prod(a1.hi, b2.hi);  // P + p = a_1·b_2 (up to η if it underflows)
  const DoubleDouble q = two_prod(a2.hi, b1.hi);
  const double c1 = std::fma(a1.hi, b2.lo, a1.lo * b2.hi);  // ≈ a_1·β_2 + α_1·b_2
  const double c2 = std::fma(a2.hi, b1.lo, a2.lo * b1.hi);
  const DoubleDouble s = two_sum(p.hi, -q.hi);  // S + s = P − Q exactly
  const double lo = ((p.lo - q.lo) + (c1 - c2)) + s.lo;
  const double magnitude = std::fabs(p.hi) + std::fabs(q.hi);
  const double propagated =
      compare_propagated_error(a1.hi, n1.radius, b1.hi, d1.radius, a2.hi, n2.radius, b2.hi, d2.radius);
  // No finiteness test: |S| ≤ M, and each term of lo is below 2^973 when M is finite, or NaN (a TwoSum
  // low part of an input's hi and lo can be), which makes hi + lo NaN and enclosure_sign uncertain; a
  // non-finite input makes M, R or the radius non-finite. So a certain sign implies finite hi and lo:
  // proofs/plane/PlaneStageTwoFinite.v, `compare_compensated_certain_finite`, `compare_compensated_twin_sound_total`.
  return {s.hi, lo,
          plus_absolute(compare_compensated_relative * magnitude + compare_propagation_factor * propagated,
                        absolute_constant(compare_absolute))};
}

// ---------------------------------------------------------------------------------------------------------
// Stage 3: compare_quotients_expansion (core/expansion_compare.hpp) on the ray–plane stage-3 expansions.

// The same from the ray–plane stage-3 expansions (num ≤ 12, den ≤ 6 components), when both are exact.
[[nodiscard]] inline Sign compare_quotients_expansion(const ExactExpansions& first,
                                                      const ExactExpansions& second) noexcept {
  if (!first.exact || !second.exact) return Sign::uncertain;
  return compare_quotients_expansion(first.num, first.den, second.num, second.den);
}

}  // namespace raykernel::detail
