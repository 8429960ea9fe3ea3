// Stage 2 of the certified cascade: a 3-term dot product in double-double (Ogita–Rump–Oishi "Dot2" with
// FMA-based TwoProduct), enclosed by an a-priori error bound of order u²·Σ|a_i b_i|. It decides the signs
// stage 1 could not (unless the value is within ~2^-100 of the terms' magnitude) and gives the enclosures
// from which round_quotient rounds t correctly. Cost over stage 1: 6 FMA, 2 TwoSum, 5 add.
#pragma once

#include "core/absolute_terms.hpp"
#include "core/dot3_filter.hpp"
#include "core/eft.hpp"
#include "core/enclosure.hpp"
#include "core/error_bounds.hpp"

#include <cmath>

namespace raykernel::detail {

// compensated_dot3: an enclosure of V = Σ (a_i + α_i)·b_i, where a_i are the values stage 1 multiplied
// (stage1.product[i] == a_i ⊗ b_i) and α_i their exact low parts, |α_i| ≤ u|a_i| (the TwoSum error of
// p_i ⊖ o_i for num). compensated_dot3_exact is the same for α = 0 (den = d·n, exact inputs): it computes
// g_i = l_i, which is what RN(0·b_i + l_i) is, without the three FMAs by zero.
//   Error bound: |V − (hi + lo)| ≤ (2^-101 ⊗ m) ⊕ 2^-1070, m the stage-1 magnitude (error_bounds.hpp).
//   Valid range: all finite inputs. Overflow needs no test of its own: |hi| ≤ m by monotonicity of
//   rounding, every term of lo is below 2^973 when m is finite, or NaN (a TwoDiff low part α_i can be: for
//   p = −(2^1022 + 3·2^970), o = −largest finite, p − o rounds to +inf inside TwoSum), and a NaN lo makes
//   hi + lo NaN, which no comparison certifies; a non-finite m makes the radius +inf or NaN ("no
//   information"). So a certain sign implies finite hi and lo, for every bit pattern of the inputs:
//   proofs/plane/PlaneStageTwoFinite.v, `den_compensated_certain_finite`, `num_compensated_certain_finite`.
//   Certified by: proofs/plane/PlaneCompensated.v, `compensated_dot3_enclosure`; the α = 0 form computes the same
//   enclosure bit for bit: proofs/plane/PlaneCascade.v, `compensated_dot3_exact_inputs`.
template <class V>
[[nodiscard]] [[gnu::always_inline]] inline EnclosureT<V> compensated_dot3_from_low_parts(const V g[3],
                                                                                          const Dot3RoundedT<V>& stage1) noexcept {
  const DD<V> s2 = two_sum(stage1.product[0], stage1.product[1]);
  const DD<V> s3 = two_sum(s2.hi, stage1.product[2]);
  const V lo = ((g[0] + g[1]) + g[2]) + (s2.lo + s3.lo);
  return {s3.hi, lo,
          plus_absolute(bounds::compensated_relative * stage1.magnitude,
                        absolute_constant(bounds::compensated_absolute))};
}

template <class V>
[[nodiscard]] [[gnu::always_inline]] inline EnclosureT<V> compensated_dot3(const V a[3], const V alpha[3], const V b[3],
                                                                           const Dot3RoundedT<V>& stage1) noexcept {
  V g[3];
  for (int i = 0; i < 3; ++i) {
    const V l = fma(a[i], b[i], -stage1.product[i]);  // l_i = RN(a_i b_i − h_i): exact unless a_i b_i underflows
    g[i] = fma(alpha[i], b[i], l);                     // g_i = RN(α_i b_i + l_i)
  }
  return compensated_dot3_from_low_parts(g, stage1);
}

template <class V>
[[nodiscard]] [[gnu::always_inline]] inline EnclosureT<V> compensated_dot3_exact(const V a[3], const V b[3],
                                                                                 const Dot3RoundedT<V>& stage1) noexcept {
  V g[3];
  for (int i = 0; i < 3; ++i) g[i] = fma(a[i], b[i], -stage1.product[i]);  // l_i
  return compensated_dot3_from_low_parts(g, stage1);
}

// compensated_dot3_refined: the same V as compensated_dot3, enclosed more tightly (error of order
// u³·Σ|a_i b_i| + u·|result|): the first-order low parts are summed with TwoSum and their errors kept.
// Used when compensated_dot3's enclosure is too wide for a sign or for the rounding of t.
//   Error bound: |V − (hi + lo)| ≤ ((2^-150 ⊗ m) ⊕ (2^-52 ⊗ |lo|)) ⊕ 8μ (error_bounds.hpp).
//   Valid range: all finite inputs; the radius is not finite if anything overflowed.
//   Certified by: proofs/plane/PlaneCompensated.v, `compensated_dot3_refined_enclosure`.
//   V is double or a Lanes type: each lane is the scalar evaluation of its own value, bit for bit (the same
//   operations, elementwise; plane/ray_plane_stages.hpp evaluates den and num as the two lanes of a Lanes2,
//   and tests/plane_stages_test.cpp compares the lanes with the scalar form).
template <class V>
[[nodiscard]] [[gnu::always_inline]] inline EnclosureT<V> compensated_dot3_refined(const V a[3], const V alpha[3], const V b[3],
                                                                                   const Dot3RoundedT<V>& stage1) noexcept {
  const DD<V> s2 = two_sum(stage1.product[0], stage1.product[1]);
  const DD<V> s3 = two_sum(s2.hi, stage1.product[2]);
  V first_order[8] = {s2.lo, s3.lo};
  V second_order[3];
  for (int i = 0; i < 3; ++i) {
    first_order[2 + i] = fma(a[i], b[i], -stage1.product[i]);  // l_i
    const DD<V> w = two_prod(alpha[i], b[i]);
    first_order[5 + i] = w.hi;
    second_order[i] = w.lo;
  }
  V sigma = first_order[0];
  V tail{};  // +0
  for (int j = 1; j < 8; ++j) {
    const DD<V> step = two_sum(sigma, first_order[j]);
    sigma = step.hi;
    tail += step.lo;
  }
  for (int i = 0; i < 3; ++i) tail += second_order[i];
  const DD<V> x = two_sum(s3.hi, sigma);
  const V lo = x.lo + tail;
  // No overflow test: the radius contains 2^-52 ⊗ |lo|, so a finite radius means a finite lo (a NaN α_i,
  // which a TwoDiff low part can be, makes lo and the radius NaN), and a finite x.lo means a finite
  // x.hi. So a certain sign implies finite hi and lo, for every bit pattern of the inputs:
  // proofs/plane/PlaneRefinedFinite.v, `den_refined_certain_finite`, `num_refined_certain_finite`.
  return {x.hi, lo,
          plus_absolute(bounds::refined_relative * stage1.magnitude + bounds::refined_low_relative * abs(lo),
                        absolute_constant(bounds::refined_absolute))};
}

}  // namespace raykernel::detail
