// Stage 1 of the certified cascade: the sign of a 3-term dot product in binary64 with a semi-static error
// bound (Shewchuk's "fast" stage; CGAL's static filters). Decides the signs of
//
//     den = d·n                  (a = d,      b = n, exact inputs)
//     num = (p − o)·n            (a = p ⊖ o,  b = n, rounded differences)
//
// from the rounded products, and says `uncertain` where the bound cannot decide. Cost: 6 mul, 6 add, 3 abs.
#pragma once

#include "certified/error_bounds.hpp"
#include "certified/sign.hpp"

#include <cmath>

namespace raykernel::detail {

// The rounded dot product of stage 1, and the magnitude its error bound is computed from. The products are
// kept: stage 2 extends them instead of recomputing them.
struct Dot3Rounded {
  double product[3];  // q_i = a_i ⊗ b_i
  double value;       // s = (q_1 ⊕ q_2) ⊕ q_3
  double magnitude;   // m = (|q_1| ⊕ |q_2|) ⊕ |q_3|
};

[[nodiscard]] inline Dot3Rounded dot3_rounded(const double a[3], const double b[3]) noexcept {
  Dot3Rounded r;
  for (int i = 0; i < 3; ++i) r.product[i] = a[i] * b[i];
  r.value = (r.product[0] + r.product[1]) + r.product[2];
  r.magnitude = (std::fabs(r.product[0]) + std::fabs(r.product[1])) + std::fabs(r.product[2]);
  return r;
}

// dot3_filter: the sign of Σ a_i b_i (exact), given the stage-1 evaluation and its relative constant
// (bounds::filter_den_relative when a holds exact values, bounds::filter_num_relative when a_i = p_i ⊖ o_i).
//   Error bound: |s − a·b| ≤ (C ⊗ m) ⊕ 3μ, C as derived in error_bounds.hpp.
//   Valid range: all finite inputs (subnormal included); uncertain if m overflows.
//   Certified by: proofs/Filter.v, `den_filter_sound` and `num_filter_sound`.
// `exactly_zero` is the caller's proof that every term has a zero factor, so the exact sum is 0 whatever
// the rounding: the only way this stage certifies zero.
[[nodiscard]] inline Sign dot3_filter(const Dot3Rounded& r, double relative_constant, bool exactly_zero) noexcept {
  if (exactly_zero) return Sign::zero;
  const double bound = relative_constant * r.magnitude + bounds::filter_absolute;
  // Branch-free: the sign of a random query is unpredictable, its certainty almost always predictable.
  const int sign = static_cast<int>(r.value > bound) - static_cast<int>(r.value < -bound);
  return sign == 0 ? Sign::uncertain : static_cast<Sign>(sign);  // 0 also when bound or value is NaN
}

}  // namespace raykernel::detail
