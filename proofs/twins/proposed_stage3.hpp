// Stage 3 as proposed for kernel/src/certified (proofs/README.md, "Stage 3: the change proposed"): the code
// of expansion.hpp, compare_quotients.hpp and intersect_certified.cpp with three changes, each one line in
// the kernel, which make stage 3 provable without Shewchuk's nonoverlapping theorems (proofs/Expansions.v):
//   1. ExpansionBuilder::sum: two_sum(take_smaller(), q) in place of fast_two_sum(take_smaller(), q);
//   2. ExpansionBuilder::scale: two_sum(p.hi, sum.hi) in place of fast_two_sum(p.hi, sum.hi);
//   3. Expansion::sign(): the checked sign below (the top component decides when it exceeds twice the
//      rounded sum of the others' magnitudes; otherwise `uncertain`, and the callers go to the exact stage:
//      certified_signs returns nullopt when either sign is uncertain).
// TwoSum gives the same sum and, whenever Fast2Sum's precondition |a| ≥ |b| holds (always, by Shewchuk's
// Theorems 13 and 19), the same error, so 1 and 2 change no answer; 3 answers `uncertain` only where the top
// component does not dominate, which nonoverlapping expansions avoid except in contrived cases. The
// differential runner checks this header against the twins (the *_p routines) and, on the same inputs,
// against the kernel's current code (driver.cpp, "current = proposed").
//
// Delete this file once the kernel has the change (and point the *_p rows of the driver at the kernel).
#pragma once

#include "certified/eft.hpp"
#include "certified/error_bounds.hpp"
#include "certified/expansion.hpp"
#include "certified/ray_plane_query.hpp"
#include "certified/sign.hpp"

#include <cmath>
#include <cstddef>
#include <optional>

namespace raykernel::detail::proposed {

// Change 3: the sign of the exact sum of an expansion, checked (proofs/Expansions.v, `expansion_sign_sound`:
// for any list of at most 2^20 finite doubles, nonoverlapping or not).
template <std::size_t N>
[[nodiscard]] Sign expansion_sign(const Expansion<N>& e) noexcept {
  const double top = e.component[e.size - 1];
  double lower = 0;
  for (std::size_t i = 0; i + 1 < e.size; ++i) lower += std::fabs(e.component[i]);
  if (lower + lower < std::fabs(top)) return top > 0 ? Sign::positive : Sign::negative;
  return (e.size == 1 && top == 0) ? Sign::zero : Sign::uncertain;
}

// ExpansionBuilder with changes 1 and 2 (otherwise expansion.hpp's, line for line).
class ExpansionBuilder {
 public:
  DoubleDouble product(double a, double b) noexcept {
    const DoubleDouble p = two_prod(a, b);
    note_product(a, b, p.hi);
    return p;
  }
  template <std::size_t N>
  void check_finite(const Expansion<N>& e) noexcept {
    for (std::size_t i = 0; i < e.size; ++i) exact_ &= std::isfinite(e.component[i]);
  }
  [[nodiscard]] bool exact() const noexcept { return exact_; }

  template <std::size_t M, std::size_t N>
  void scale(const Expansion<M>& e, double b, Expansion<N>& h) noexcept {
    static_assert(N >= 2 * M);
    h.size = 0;
    DoubleDouble p = product(e.component[0], b);
    double q = p.hi;
    push(h, p.lo);
    for (std::size_t i = 1; i < e.size; ++i) {
      p = product(e.component[i], b);
      const DoubleDouble sum = two_sum(q, p.lo);
      push(h, sum.lo);
      const DoubleDouble next = two_sum(p.hi, sum.hi);  // change 2
      push(h, next.lo);
      q = next.hi;
    }
    finish(h, q);
  }

  template <std::size_t M, std::size_t N, std::size_t K>
  static void sum(const Expansion<M>& e, const Expansion<N>& f, Expansion<K>& h) noexcept {
    static_assert(K >= M + N);
    std::size_t ei = 0, fi = 0;
    auto take_smaller = [&]() -> double {
      if (fi >= f.size) return e.component[ei++];
      if (ei >= e.size) return f.component[fi++];
      const double en = e.component[ei], fn = f.component[fi];
      if ((fn > en) == (fn > -en)) {
        ++ei;
        return en;
      }
      ++fi;
      return fn;
    };
    h.size = 0;
    double q = take_smaller();
    if (ei < e.size || fi < f.size) {
      const DoubleDouble s = two_sum(take_smaller(), q);  // change 1
      push(h, s.lo);
      q = s.hi;
      while (ei < e.size || fi < f.size) {
        const DoubleDouble t = two_sum(q, take_smaller());
        push(h, t.lo);
        q = t.hi;
      }
    }
    finish(h, q);
  }

  template <std::size_t N>
  static void from_pair(const DoubleDouble& p, Expansion<N>& h) noexcept {
    static_assert(N >= 2);
    h.size = 0;
    push(h, p.lo);
    finish(h, p.hi);
  }

 private:
  void note_product(double a, double b, double p) noexcept {
    const bool exact = (p == 0) ? (a == 0 || b == 0) : (std::fabs(p) >= 0x1p-968);
    exact_ &= exact && std::isfinite(p);
  }
  template <std::size_t N>
  static void push(Expansion<N>& h, double x) noexcept {
    if (x != 0) h.component[h.size++] = x;
  }
  template <std::size_t N>
  static void finish(Expansion<N>& h, double q) noexcept {
    if (q != 0 || h.size == 0) h.component[h.size++] = q;
  }

  bool exact_ = true;
};

// ray_plane_query.hpp's ray_plane_expansions with the builder above.
[[nodiscard]] inline ExactExpansions build_expansions(const RayPlaneTerms& q) noexcept {
  ExpansionBuilder builder;
  Expansion<12> num;
  Expansion<6> den;
  {
    Expansion<2> product[3];
    for (int i = 0; i < 3; ++i) ExpansionBuilder::from_pair(builder.product(q.d[i], q.n[i]), product[i]);
    Expansion<4> partial;
    ExpansionBuilder::sum(product[0], product[1], partial);
    ExpansionBuilder::sum(partial, product[2], den);
  }
  {
    Expansion<4> term[3];
    for (int i = 0; i < 3; ++i) {
      Expansion<2> difference;
      ExpansionBuilder::from_pair(two_diff(q.p[i], q.o[i]), difference);
      builder.scale(difference, q.n[i], term[i]);
    }
    Expansion<8> partial;
    ExpansionBuilder::sum(term[0], term[1], partial);
    ExpansionBuilder::sum(partial, term[2], num);
  }
  builder.check_finite(num);
  builder.check_finite(den);
  return {num, den, builder.exact()};
}

// compare_quotients.hpp's multiply_expansions and compare_quotients_expansion with the builder above and
// the checked sign.
template <std::size_t M, std::size_t N>
void multiply_expansions(ExpansionBuilder& builder, const Expansion<M>& e, const Expansion<N>& f,
                         Expansion<2 * M * N>& product) noexcept {
  Expansion<2 * M * N> partial;
  builder.scale(e, f.component[0], partial);  // fits: 2·M ≤ 2·M·N
  for (std::size_t j = 1; j < f.size; ++j) {
    Expansion<2 * M> term;
    builder.scale(e, f.component[j], term);
    Expansion<2 * M * N + 2 * M> next;
    ExpansionBuilder::sum(partial, term, next);
    partial.size = next.size;  // at most 2·M·(j+1) ≤ 2·M·N components
    for (std::size_t i = 0; i < next.size; ++i) partial.component[i] = next.component[i];
  }
  product = partial;
}

[[nodiscard]] inline Sign compare_quotients_expansion(const ExactExpansions& first, const ExactExpansions& second) noexcept {
  if (!first.exact || !second.exact) return Sign::uncertain;
  ExpansionBuilder builder;
  Expansion<2 * 12 * 6> n1_d2, n2_d1;
  multiply_expansions(builder, first.num, second.den, n1_d2);
  multiply_expansions(builder, second.num, first.den, n2_d1);
  for (std::size_t i = 0; i < n2_d1.size; ++i) n2_d1.component[i] = -n2_d1.component[i];
  Expansion<2 * 2 * 12 * 6> delta;
  ExpansionBuilder::sum(n1_d2, n2_d1, delta);
  builder.check_finite(n1_d2);
  builder.check_finite(n2_d1);
  builder.check_finite(delta);
  if (!builder.exact()) return Sign::uncertain;
  return expansion_sign(delta);
}

}  // namespace raykernel::detail::proposed
