// The error bounds' absolute terms, added without a subnormal operand.
//
// Every error bound of the certified stages ends in an absolute term μ_B — a small multiple of 2^-1074
// (error_bounds.hpp: 3μ, 8μ, 2^-1070, ...) — that covers products which underflow: B = X ⊕ μ_B. Those constants
// are subnormal, and on x86 an operation with a subnormal operand raises the denormal-operand flag (MXCSR.DE);
// a sticky flag that goes from clear to set costs a microcode assist, and every public call then clears it
// again when it restores the caller's flags (fp_environment.hpp). Measured on the degenerate plane workload
// (the caller's flags holding inexact, as after any inexact operation): 217 ns a query with the constants as
// operands, 130 ns with DE already set — the difference is that assist, paid by every call. So the sums are
// formed here, bit for bit the same, from normal operands only.
//
// plus_absolute(x, absolute_constant(M)) = RN(x + M), M = k·2^-1074 with 1 ≤ k ≤ 2^18 (the constants above), for
// every double x:
//
//   |x| ≥ T = 2^-1000 (and ±inf, NaN): RN(x + M) = x, since the doubles next to x on either side are at least
//     2^-1053 away and M ≤ 2^-1056 is less than half of that (for NaN and ±inf, x + M is x). So the answer is x.
//   |x| < T: every double is a multiple of 2^-1074, so x + M = S is one, with |S| < 2^-999. With L = 2^600,
//     x ⊗ L = x·L and M·L (a constant) are exact and normal (or zero: x = ±0), and RN(x·L + M·L) = L·RN(S):
//     where |S| ≥ 2^-1022 both roundings are to 53 significant bits in the normal range, and scaling by a power
//     of two commutes with them; where |S| < 2^-1022, S is a subnormal double (RN(S) = S) and L·S, a multiple
//     of 2^-474 below 2^-422, has at most 52 significant bits (RN(L·S) = L·S). Then ⊗ 2^-600 is exact: it gives
//     the double RN(S). The operand of that last product is normal, and x·L is computed from x clamped to
//     [−T, T] in every lane (the lanes with |x| ≥ T take x), so no lane forms anything subnormal or overflows
//     — except from a subnormal x itself (an input so small that its own operations raise the flag anyway).
//
// The same bits as X ⊕ M for every input, so every proof of a bound written X ⊕ M (and every twin, whose
// models compute X ⊕ M) holds unchanged: tests/fp_environment_test.cpp (AbsoluteTerms) checks it bit for bit on
// each constant, for one value and per lane, across the binades around T and 2^-1022, signed zeros, subnormals,
// ±inf, NaN and random bit patterns; the twin runner compares the C++ bounds with the models' X ⊕ M on every
// routine. det3_stages.hpp's det3_absolute_term is the same idea for the determinants' dynamic term
// (K_A ⊗ S) ⊕ U_A, which plus_absolute_term below then adds to a bound.
//
// Not covered: a bound whose operand x is itself subnormal (inputs near the subnormal range), and stage 3's
// tail enclosures, whose radius is the subnormal 2^-1073 when the tail is zero and is then an operand of
// round_quotient: those queries raise the flag, and pay the assist, as their own arithmetic on tiny values does.
#pragma once

#include "core/lanes.hpp"

#include <cmath>
#include <cstddef>
#include <type_traits>

namespace raykernel::detail {

inline constexpr double absolute_sum_threshold = 0x1p-1000;  // T: below it in magnitude, the lifted sum
inline constexpr double absolute_sum_lift = 0x1p600;         // L
inline constexpr double absolute_sum_drop = 0x1p-600;        // 1/L

// An absolute constant M and M·L, checked when the program is compiled (a function argument rather than a
// template parameter of type double, which clang 14 does not accept).
struct AbsoluteConstant {
  double m, lifted;
};
consteval AbsoluteConstant absolute_constant(double m) {
  if (!(m >= 0x1p-1074 && m <= 0x1p-1056)) throw "an absolute term: k·2^-1074 with 1 ≤ k ≤ 2^18";
  return {m, m * absolute_sum_lift};  // exact: a normal number
}

// RN(x + M) (see above), c = absolute_constant(M). V is double or a Lanes type.
template <class V>
[[nodiscard]] [[gnu::always_inline]] inline V plus_absolute(V x, AbsoluteConstant c) noexcept {
  if constexpr (std::is_same_v<V, double>) {
    // One value: a branch, taken only for the (rare) bounds below T.
    if (abs(x) < absolute_sum_threshold) [[unlikely]]
      return (x * absolute_sum_lift + c.lifted) * absolute_sum_drop;
    return x;
  } else {
    // On doubles only (the "fma" clone has no 256-bit integer operations). Returns at once when no lane needs
    // the lifted sum: a branch the predictor learns, so that the bound's latency stays about the plain sum's
    // (the lifted sum blended into every lane put about 15 cycles on the critical path of a relation query:
    // +15% measured).
    const auto small = abs(x) < V{} + absolute_sum_threshold;
    if (!any_lane(small)) [[likely]]
      return x;
    const V safe = select(small, x, V{} + absolute_sum_threshold);
    const V lifted = (safe * absolute_sum_lift + c.lifted) * absolute_sum_drop;
    return select(small, lifted, x);
  }
}

// RN(x + a) for a dynamic absolute term a ≥ 0 (the determinants' A, det3_stages.hpp: subnormal for every input
// of ordinary size), for every double x, without a subnormal operand unless x is one:
//
//   a ≥ 2^-1022, ±inf or NaN: x ⊕ a as written (a is not subnormal).
//   a < 2^-1022 (subnormal or zero), |x| ≥ T_a = 2^-968 or x NaN: RN(x + a) = x, since the doubles next to x are
//     at least 2^-1021 away and a < 2^-1022 is less than half of that.
//   a < 2^-1022, |x| < T_a: the lifted sum, as above, with a·L = n·2^-474 formed from a's bit pattern n = a/2^-1074
//     (n < 2^52: the bits of 2^52 or'ed with n are those of 2^52 + n, and (2^52 + n) ⊖ 2^52 = n exactly) instead of
//     from a.
//
// a's size is read from its bits (comparing a subnormal raises the flag too). a must have its sign bit clear (an
// error bound's term is +0 or more, or NaN). The same bits as x ⊕ a for every x and every such a:
// tests/fp_environment_test.cpp (AbsoluteTerms) checks it as above.
inline constexpr double absolute_term_threshold = 0x1p-968;  // T_a
inline constexpr double smallest_normal = 0x1p-1022;
inline constexpr double integer_shift = 0x1p52;              // 2^52 + n for n < 2^52 from the bits
inline constexpr double lifted_unit = 0x1p-474;              // 2^-1074·L

template <class V>
[[nodiscard]] [[gnu::always_inline]] inline V plus_absolute_term(V x, V a) noexcept {
  if constexpr (std::is_same_v<V, double>) {
    if (to_bits(a) < to_bits(smallest_normal)) [[likely]] {
      if (!(abs(x) < absolute_term_threshold)) [[likely]]
        return x;
      const double a_lifted = (from_bits(to_bits(integer_shift) | to_bits(a)) - integer_shift) * lifted_unit;
      return (x * absolute_sum_lift + a_lifted) * absolute_sum_drop;
    }
    return x + a;
  } else {
    // On doubles only (bitwise and/or are vandpd/vorpd: the "fma" clone has no 256-bit integer operations). a's
    // exponent field alone, as a double, is +0 exactly when a is subnormal or zero, a normal number or inf
    // otherwise: comparing it raises nothing.
    const V exponent = from_bits(to_bits(a) & (to_bits(V{} + HUGE_VAL)));
    const auto a_small = exponent == V{};
    const auto x_small = abs(x) < V{} + absolute_term_threshold;
    // x ⊕ a where a is not small, x ⊕ 0 = x where it is and x is not (|x| ≥ T_a: x is not −0); the lanes where
    // both are small take the lifted sum below.
    const V common = x + select(a_small, V{}, a);
    const auto both_small = a_small & x_small;
    if (!any_lane(both_small)) [[likely]]
      return common;
    const V a_safe = select(both_small, a, V{});  // n·2^-1074 where the lifted sum is taken, +0 elsewhere
    const V a_lifted = (from_bits(to_bits(a_safe) | to_bits(V{} + integer_shift)) - integer_shift) * lifted_unit;
    const V x_safe = select(x_small, x, V{} + absolute_term_threshold);
    const V lifted = (x_safe * absolute_sum_lift + a_lifted) * absolute_sum_drop;
    return select(both_small, lifted, common);
  }
}

}  // namespace raykernel::detail
