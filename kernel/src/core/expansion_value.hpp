// Stage 3 of the certified ray–triangle cascade: ray_triangle_formula.hpp evaluated in exact floating-point
// expansions, with core/expansion.hpp's ExpansionBuilder doing the arithmetic. An
// ExpansionValue<N> holds an expansion of capacity N (a compile-time bound on its length, which zero
// elimination keeps far from reached) and whether it is exact: every TwoProduct was exact (no underflow)
// and nothing overflowed. Sign decisions use a value only when `exact`; otherwise the exact rational stage
// decides.
//
// The formula multiplies a leaf (d or a difference: at most 2 components) by a cross component, or two
// leaves: the product scales the longer operand by each component of the shorter and sums the scaled
// expansions (ExpansionBuilder::scale and ::sum, exact by proofs/core/Expansions.v). Capacities: leaf 2,
// leaf·leaf 8, cross component 16, leaf·cross 64, π and num 192, den 576.
//
// Certified by: proofs/triangle/TriangleStage3Twins.v, `value_ev_exact` (every operation below and
// ray_triangle_stages.hpp's value_expansion as a twin: when `exact`, the components are finite and sum to the
// exact πa, πb, πc, den or num) and `triangle_expansion_sign_sound` (so `sign()` is the exact sign); the twin
// is compared bit for bit with this code by the differential runner (routine tri_expansion).
#pragma once

#include "core/eft.hpp"
#include "core/expansion.hpp"
#include "core/sign.hpp"

#include <cstddef>

namespace raykernel::detail {

template <std::size_t N>
struct ExpansionValue {
  Expansion<N> e;
  bool exact = true;

  ExpansionValue() noexcept = default;
  // Copies only the components in use (the capacity is a compile-time bound, mostly unused).
  ExpansionValue(const ExpansionValue& other) noexcept : exact(other.exact) { copy_components(other); }
  ExpansionValue& operator=(const ExpansionValue& other) noexcept {
    exact = other.exact;
    copy_components(other);
    return *this;
  }
  void copy_components(const ExpansionValue& other) noexcept {
    e.size = other.e.size;
    for (std::size_t i = 0; i < other.e.size; ++i) e.component[i] = other.e.component[i];
  }

  [[nodiscard]] Sign sign() const noexcept { return exact ? e.sign() : Sign::uncertain; }
};

// An input double (a 1-component expansion; 0 is the expansion {0}), in a leaf's capacity.
[[nodiscard]] inline ExpansionValue<2> expansion_of(double x) noexcept {
  ExpansionValue<2> v;
  v.e.component[0] = x;
  v.e.size = 1;
  v.exact = std::isfinite(x);
  return v;
}

// v − w exactly (TwoDiff).
[[nodiscard]] inline ExpansionValue<2> expansion_difference(double v, double w) noexcept {
  ExpansionValue<2> r;
  ExpansionBuilder::from_pair(two_diff(v, w), r.e);
  r.exact = std::isfinite(r.e.component[0]) && std::isfinite(r.e.component[r.e.size - 1]);
  return r;
}

template <std::size_t M, std::size_t N>
[[nodiscard]] ExpansionValue<M + N> operator+(const ExpansionValue<M>& a, const ExpansionValue<N>& b) noexcept {
  ExpansionValue<M + N> r;
  ExpansionBuilder::sum(a.e, b.e, r.e);
  ExpansionBuilder check;
  check.check_finite(r.e);
  r.exact = a.exact && b.exact && check.exact();
  return r;
}

template <std::size_t N>
[[nodiscard]] ExpansionValue<N> operator-(const ExpansionValue<N>& a) noexcept {
  ExpansionValue<N> r = a;
  for (std::size_t i = 0; i < a.e.size; ++i) r.e.component[i] = -a.e.component[i];  // exact
  return r;
}

template <std::size_t M, std::size_t N>
[[nodiscard]] ExpansionValue<M + N> operator-(const ExpansionValue<M>& a, const ExpansionValue<N>& b) noexcept {
  return a + (-b);
}

// a·b with b a leaf (at most 2 components): scale(a, b_0) + scale(a, b_1).
template <std::size_t M>
[[nodiscard]] ExpansionValue<4 * M> operator*(const ExpansionValue<M>& a, const ExpansionValue<2>& b) noexcept {
  ExpansionBuilder builder;
  ExpansionValue<4 * M> r;
  if (b.e.size == 1) {
    builder.scale(a.e, b.e.component[0], r.e);  // the one scaled expansion, built in place
  } else {
    Expansion<2 * M> first;
    builder.scale(a.e, b.e.component[0], first);
    Expansion<2 * M> second;
    builder.scale(a.e, b.e.component[1], second);
    ExpansionBuilder::sum(first, second, r.e);
  }
  builder.check_finite(r.e);
  r.exact = a.exact && b.exact && builder.exact();
  return r;
}

// The formula writes leaf·leaf and leaf·cross component with the leaf first.
template <std::size_t M>
  requires(M != 2)
[[nodiscard]] ExpansionValue<4 * M> operator*(const ExpansionValue<2>& leaf, const ExpansionValue<M>& a) noexcept {
  return a * leaf;
}

}  // namespace raykernel::detail
