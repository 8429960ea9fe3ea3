// Stage 1 of the certified cascade: the sign of a 3-term dot product in binary64 with a semi-static error
// bound (Shewchuk's "fast" stage; CGAL's static filters). Decides the signs of
//
//     den = d·n                  (a = d,      b = n, exact inputs)
//     num = (p − o)·n            (a = p ⊖ o,  b = n, rounded differences)
//
// from the rounded products, and says `uncertain` where the bound cannot decide. Cost: 6 mul, 6 add, 3 abs.
#pragma once

#include "core/absolute_terms.hpp"
#include "core/error_bounds.hpp"
#include "core/sign.hpp"

#include <cmath>

namespace raykernel::detail {

// The rounded dot product of stage 1, and the magnitude its error bound is computed from. The products are
// kept: stage 2 extends them instead of recomputing them. V is double, or Lanes8 for eight queries at once.
template <class V>
struct Dot3RoundedT {
  V product[3];  // q_i = a_i ⊗ b_i
  V value;       // s = (q_1 ⊕ q_2) ⊕ q_3
  V magnitude;   // m = (|q_1| ⊕ |q_2|) ⊕ |q_3|
};
using Dot3Rounded = Dot3RoundedT<double>;

template <class V>
[[nodiscard]] [[gnu::always_inline]] inline Dot3RoundedT<V> dot3_rounded(const V a[3], const V b[3]) noexcept {
  Dot3RoundedT<V> r;
  for (int i = 0; i < 3; ++i) r.product[i] = a[i] * b[i];
  r.value = (r.product[0] + r.product[1]) + r.product[2];
  r.magnitude = (abs(r.product[0]) + abs(r.product[1])) + abs(r.product[2]);
  return r;
}

// The same for a·a: each q_i = a_i ⊗ a_i ≥ 0 (RN is monotone and RN(0) = 0), so |q_i| = q_i and the magnitude's
// sums are the value's, bit for bit (proofs/sphere/SphereFilter.v, `square_magnitude_value`); it is copied instead of
// recomputed.
template <class V>
[[nodiscard]] [[gnu::always_inline]] inline Dot3RoundedT<V> dot3_rounded_square(const V a[3]) noexcept {
  Dot3RoundedT<V> r;
  for (int i = 0; i < 3; ++i) r.product[i] = a[i] * a[i];
  r.value = (r.product[0] + r.product[1]) + r.product[2];
  r.magnitude = r.value;
  return r;
}

// dot3_filter: the sign of Σ a_i b_i (exact), given the stage-1 evaluation and its relative constant
// (bounds::filter_den_relative when a holds exact values, bounds::filter_num_relative when a_i = p_i ⊖ o_i).
//   Error bound: |s − a·b| ≤ (C ⊗ m) ⊕ 3μ, C as derived in error_bounds.hpp.
//   Valid range: all finite inputs (subnormal included); uncertain if m overflows.
//   Certified by: proofs/plane/PlaneFilter.v, `den_filter_sound` and `num_filter_sound`; dot3_filter_lanes alone (no
//   zero flag, the fast path): proofs/plane/PlaneFilter.v, `den_filter_lanes_sound` and `num_filter_lanes_sound`.
// dot3_filter_lanes gives the sign as an integer (Sign's values) per lane; branch-free: the sign of a random
// query is unpredictable, its certainty almost always predictable. Neither comparison holds when the bound
// or the value is NaN: uncertain.
// The bound itself, B = (C ⊗ m) ⊕ 3μ: |s − a·b| ≤ B (proofs/plane/PlaneFilter.v, `den_filter_encloses`,
// `num_filter_encloses`). Every stage-1 decision compares against it.
// (The constant is a double, or one per lane: den's and num's when a vector holds both of one query.)
template <class V, class C>
[[nodiscard]] [[gnu::always_inline]] inline V dot3_filter_bound(const Dot3RoundedT<V>& r, C relative_constant) noexcept {
  // ⊕ 3μ without a subnormal operand (core/absolute_terms.hpp)
  return plus_absolute(relative_constant * r.magnitude, absolute_constant(bounds::filter_absolute));
}

template <class V, class C>
[[nodiscard]] [[gnu::always_inline]] inline IntegerOf<V> dot3_filter_lanes(const Dot3RoundedT<V>& r,
                                                                           C relative_constant) noexcept {
  const V bound = dot3_filter_bound(r, relative_constant);
  return sign_lanes(r.value > bound, r.value < -bound);
}

// The same for one query. `exactly_zero` is the caller's proof that every term has a zero factor, so the
// exact sum is 0 whatever the rounding: the only way this stage certifies zero.
[[nodiscard]] inline Sign dot3_filter(const Dot3Rounded& r, double relative_constant, bool exactly_zero) noexcept {
  if (exactly_zero) return Sign::zero;
  return static_cast<Sign>(dot3_filter_lanes(r, relative_constant));
}

}  // namespace raykernel::detail
