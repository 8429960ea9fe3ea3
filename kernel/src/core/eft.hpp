// Error-free transformations of binary64 arithmetic (round to nearest, ties to even).
//
// Each routine returns a pair (hi, lo) whose exact sum equals an exact real result, under the condition
// stated with it. They are the building blocks of the compensated and expansion stages.
//
// References: Knuth, TAOCP vol. 2, §4.2.2 (TwoSum); Dekker 1971 (Fast2Sum); Ogita, Rump, Oishi, "Accurate
// sum and dot product", SIAM J. Sci. Comput. 26(6), 2005 (TwoProduct with FMA); Shewchuk, "Adaptive
// precision floating-point arithmetic and fast robust geometric predicates", DCG 18, 1997, §2.
// Flocq proves the exactness lemmas used here: `plus_error` (TwoSum) and `mult_error_FLT` (TwoProduct).
#pragma once

#include "core/lanes.hpp"

#include <cmath>

namespace raykernel::detail {

// An unevaluated sum hi + lo of two doubles (per lane, for Lanes8).
template <class V>
struct DD {
  V hi;
  V lo;
};
using DoubleDouble = DD<double>;

// Knuth's TwoSum: hi = a ⊕ b and hi + lo == a + b exactly, for all finite a, b whose sum does not
// overflow (the error of a rounded sum is always representable, Flocq `plus_error`, even with gradual
// underflow). Six operations, no branch, no precondition on the magnitudes.
template <class V>
[[nodiscard]] [[gnu::always_inline]] inline DD<V> two_sum(V a, V b) noexcept {
  const V s = a + b;
  const V b_virtual = s - a;
  const V a_virtual = s - b_virtual;
  const V b_roundoff = b - b_virtual;
  const V a_roundoff = a - a_virtual;
  return {s, a_roundoff + b_roundoff};
}

// TwoSum of a and −b: hi = a ⊖ b and hi + lo == a − b exactly (same conditions as two_sum).
template <class V>
[[nodiscard]] [[gnu::always_inline]] inline DD<V> two_diff(V a, V b) noexcept {
  return two_sum(a, -b);
}

// TwoProduct with a fused multiply-add: hi = a ⊗ b and lo = RN(a·b − hi). The pair is exact
// (hi + lo == a·b) when a·b == 0 or |a·b| ≥ 2^-969 = 2^(emin + 2p − 1) (Flocq `mult_error_FLT`), and no
// overflow occurs. Otherwise |a·b − hi − lo| ≤ 2^-1075: a·b − hi is then below 2^-1022 and its rounding is
// an absolute error of at most half the smallest subnormal. fma is correctly rounded whether the compiler
// emits the instruction or calls libm, so the semantics do not depend on the target.
template <class V>
[[nodiscard]] [[gnu::always_inline]] inline DD<V> two_prod(V a, V b) noexcept {
  const V p = a * b;
  return {p, fma(a, b, -p)};
}

}  // namespace raykernel::detail
