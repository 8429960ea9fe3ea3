// Exact products of expansions and the exact order of two quotients of expansions: the stage-3 comparison of
// the nearest-hit order (nearest/compare_quotients.hpp) and the sign at a rounding boundary of a quotient
// (core/quotient_boundary.hpp). Everything is exact or says it is not (ExpansionBuilder's `exact`).
#pragma once

#include "core/expansion.hpp"
#include "core/sign.hpp"

#include <cstddef>

namespace raykernel::detail {

namespace compare_internal {

template <std::size_t M, std::size_t K>
void copy_expansion(const Expansion<M>& from, Expansion<K>& to) noexcept {
  static_assert(K >= M);
  for (std::size_t i = 0; i < from.size; ++i) to.component[i] = from.component[i];
  to.size = from.size;
}

// partial + e·(f_J + f_{J+1} + ...), by scaling e by each remaining component of f and summing
// (expansion.hpp's scale and sum).
template <std::size_t J, std::size_t M, std::size_t N, std::size_t K>
void accumulate_scaled(ExpansionBuilder& builder, const Expansion<M>& e, const Expansion<N>& f,
                       const Expansion<K>& partial, Expansion<2 * M * N>& product) noexcept {
  if constexpr (J == N) {
    copy_expansion(partial, product);
  } else {
    if (J >= f.size) {
      copy_expansion(partial, product);
      return;
    }
    Expansion<2 * M> term;
    builder.scale(e, f.component[J], term);
    Expansion<K + 2 * M> next;
    ExpansionBuilder::sum(partial, term, next);
    accumulate_scaled<J + 1>(builder, e, f, next, product);
  }
}

}  // namespace compare_internal

// product = e·f exactly (when `builder.exact()` stays true): at most 2·|e|·|f| components.
template <std::size_t M, std::size_t N>
void multiply_expansions(ExpansionBuilder& builder, const Expansion<M>& e, const Expansion<N>& f,
                         Expansion<2 * M * N>& product) noexcept {
  Expansion<2 * M> first;
  builder.scale(e, f.component[0], first);
  compare_internal::accumulate_scaled<1>(builder, e, f, first, product);
}

// compare_quotients_expansion: the exact sign of Δ = N_1·D_2 − N_2·D_1 from exact expansions of num and den of
// both queries, or `uncertain` when a product in Δ is not exact (a TwoProduct underflowed, or something
// overflowed): then the exact stage decides. The expansions' capacities are compile-time bounds only; what is
// computed depends on their components alone, so every instantiation performs the operations of the one model.
//   Valid range: at most 16 components in each of the four inputs (the theorem's hypothesis; the callers check it
//   or their capacities guarantee it).
//   Certified by: proofs/core/Expansions.v, `compare_quotients_expansion_sound` (a certain sign is the sign of
//   Δ for the exact sums of the inputs; with `build_expansions_exact`, of the exact num and den).
template <std::size_t A, std::size_t B, std::size_t C, std::size_t D>
[[nodiscard]] inline Sign compare_quotients_expansion(const Expansion<A>& num1, const Expansion<B>& den1,
                                                      const Expansion<C>& num2, const Expansion<D>& den2) noexcept {
  static_assert(A <= 16 && B <= 16 && C <= 16 && D <= 16);
  ExpansionBuilder builder;
  Expansion<2 * A * D> n1_d2;
  Expansion<2 * C * B> n2_d1;
  multiply_expansions(builder, num1, den2, n1_d2);
  multiply_expansions(builder, num2, den1, n2_d1);
  for (std::size_t i = 0; i < n2_d1.size; ++i) n2_d1.component[i] = -n2_d1.component[i];  // exact
  Expansion<2 * A * D + 2 * C * B> delta;
  ExpansionBuilder::sum(n1_d2, n2_d1, delta);
  builder.check_finite(n1_d2);
  builder.check_finite(n2_d1);
  builder.check_finite(delta);
  if (!builder.exact()) return Sign::uncertain;
  return delta.sign();
}

}  // namespace raykernel::detail
