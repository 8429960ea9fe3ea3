// Stage 3 of the certified cascade: exact arithmetic on floating-point expansions (Shewchuk, "Adaptive
// precision floating-point arithmetic and fast robust geometric predicates", DCG 18, 1997).
//
// An expansion is an unevaluated sum of doubles whose exact sum is the value it stands for; zero is the single
// component 0 (zero elimination). TwoSum is exact for finite sums, TwoProduct only when the product does not
// underflow (|a·b| ≥ 2^-969, Flocq `mult_error_FLT`): every product goes through `ExpansionBuilder::product`,
// which records whether that held. A stage-3 result is used only when `exact()` is true; otherwise the cascade
// goes to the exact rational stage. Overflow shows up as a non-finite component and is caught the same way.
//
// The routines follow Shewchuk's fast_expansion_sum_zeroelim and scale_expansion_zeroelim with two changes
// that make them provable without his nonoverlapping theorems (proofs/core/Expansions.v): TwoSum everywhere
// (where he uses Fast2Sum, whose exactness needs |a| ≥ |b|, an invariant of his Theorems 13 and 19), and a
// checked sign (his sign of the largest component needs the expansion to be nonoverlapping). On the
// expansions his algorithms produce, TwoSum returns the same pair as Fast2Sum and the checked sign decides,
// so the changes cost a few additions and leave stage 3's answers as they were. TwoProduct is FMA-based in
// place of Veltkamp splitting. Round-to-nearest is required (the default environment, fp_environment.hpp).
#pragma once

#include "core/absolute_terms.hpp"
#include "core/eft.hpp"
#include "core/enclosure.hpp"
#include "core/error_bounds.hpp"
#include "core/sign.hpp"

#include <cassert>
#include <cmath>
#include <cstddef>
#include <optional>

namespace raykernel::detail {

template <std::size_t Capacity>
struct Expansion {
  double component[Capacity];  // the first `size` are meaningful (left uninitialized: this is a hot path)
  std::size_t size = 0;        // ≥ 1 once built; the zero expansion is {0}

  // The sign of the exact sum, or `uncertain`: the last component decides when its magnitude exceeds twice the
  // rounded sum of the others' magnitudes (then it exceeds their exact sum); the single component 0 is zero; and
  // a nonzero last component decides when no other component has the opposite sign (a sum of terms of one sign:
  // {−2^-64, −2^-63}, which TwoSum chains leave at exact ties, is negative though its top is not twice the rest).
  //   Valid range: finite components (callers check `exact()` first), at most 2^20 of them.
  //   Certified by: proofs/core/Expansions.v, `expansion_sign_sound` (any list of finite doubles, nonoverlapping
  //   or not; the last rule by `sum_list_weakly_signed`); `uncertain` sends the caller to the exact stage.
  [[nodiscard]] Sign sign() const noexcept {
    static_assert(Capacity <= (std::size_t{1} << 20));
    const double top = component[size - 1];
    double lower = 0;
    bool one_sign = true;  // no lower component of the sign opposite to top's
    for (std::size_t i = 0; i + 1 < size; ++i) {
      lower += std::fabs(component[i]);
      one_sign = one_sign && (top > 0 ? component[i] >= 0 : component[i] <= 0);
    }
    if (lower + lower < std::fabs(top)) return top > 0 ? Sign::positive : Sign::negative;
    if (size == 1 && top == 0) return Sign::zero;
    if (top != 0 && one_sign) return top > 0 ? Sign::positive : Sign::negative;
    return Sign::uncertain;
  }
};

// e in capacity K, when it has at most K components (round_quotient_near is proved for 16); nothing otherwise.
template <std::size_t K, std::size_t N>
[[nodiscard]] std::optional<Expansion<K>> shortened(const Expansion<N>& e) noexcept {
  if (e.size > K) return std::nullopt;
  Expansion<K> short_form;
  for (std::size_t i = 0; i < e.size; ++i) short_form.component[i] = e.component[i];
  short_form.size = e.size;
  return short_form;
}

// Builds expansions and keeps the one condition exactness depends on besides round-to-nearest: that no
// TwoProduct underflowed and nothing overflowed.
class ExpansionBuilder {
 public:
  // a·b as a 1- or 2-component expansion (zero-eliminated).
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

  // h = e·b (Shewchuk's scale_expansion_zeroelim with TwoSum for his Fast2Sum). h has at most 2·|e| components.
  //   Certified by: proofs/core/Expansions.v, `scale_gen_exact` (Σh = b·Σe when exact() and h finite).
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
      const DoubleDouble next = two_sum(p.hi, sum.hi);
      push(h, next.lo);
      q = next.hi;
    }
    finish(h, q);
  }

  // h = e + f (Shewchuk's fast_expansion_sum_zeroelim with TwoSum for his Fast2Sum), merging by increasing
  // magnitude. Certified by: proofs/core/Expansions.v, `sum_gen_exact` (Σh = Σe + Σf when h is finite).
  template <std::size_t M, std::size_t N, std::size_t K>
  static void sum(const Expansion<M>& e, const Expansion<N>& f, Expansion<K>& h) noexcept {
    static_assert(K >= M + N);
    std::size_t ei = 0, fi = 0;
    // The next component in magnitude order; ties take f's (as predicates.c does).
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
      const DoubleDouble s = two_sum(take_smaller(), q);
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

  // h = e with fewer components (Shewchuk's compress, with TwoSum for his Fast2Sum): one pass from the largest
  // component down, keeping each nonzero error term's partner, then one pass back up. Every step is a TwoSum, so
  // Σh = Σe exactly whatever e's components (no nonoverlapping invariant is needed); on the nonoverlapping
  // expansions scale and sum produce, h is nonoverlapping with at most as many components as the value's bits
  // need (two or three for the sphere's A, B, C), which is what makes later products short.
  //   Certified by: proofs/core/ExpansionCompress.v, `compress_gen_exact` (Σh = Σe when e's components are finite and h's
  //   are: every TwoSum exact).
  template <std::size_t N>
  static void compress(const Expansion<N>& e, Expansion<N>& h) noexcept {
    std::size_t kept = e.size;  // the first pass keeps its large parts in h[kept, e.size)
    double q = e.component[e.size - 1];
    for (std::size_t i = e.size - 1; i-- > 0;) {
      const DoubleDouble s = two_sum(q, e.component[i]);
      if (s.lo != 0) {
        h.component[--kept] = s.hi;
        q = s.lo;
      } else {
        q = s.hi;
      }
    }
    std::size_t top = 0;  // the second pass writes h[0, top) below what it reads (top ≤ i − kept)
    for (std::size_t i = kept; i < e.size; ++i) {
      const DoubleDouble s = two_sum(h.component[i], q);
      if (s.lo != 0) h.component[top++] = s.lo;
      q = s.hi;
    }
    h.component[top] = q;
    h.size = top + 1;
  }

  // e's sign: Expansion::sign, or when it cannot read it (a sum of expansions that overlap, as after a heavy
  // cancellation), the sign of e compressed, whose top component dominates the rest.
  //   Certified by: proofs/core/Expansions.v, `expansion_sign_sound` (on e, or on its compression) and
  //   proofs/core/ExpansionCompress.v, `compress_gen_exact` (the compression has e's exact sum); the two tries
  //   composed: proofs/sphere/SphereStages.v, `sphere_sign_or_compressed_sound` and `compress_finite_or_uncertain`
  //   (a certain answer is the sign of e's exact sum; compress(e), not checked, is finite or its sign uncertain).
  template <std::size_t N>
  [[nodiscard]] static Sign sign_or_compressed(const Expansion<N>& e) noexcept {
    const Sign direct = e.sign();
    if (is_certain(direct)) return direct;
    Expansion<N> h;
    compress(e, h);
    return h.sign();
  }

  template <std::size_t N>
  static void from_pair(const DoubleDouble& p, Expansion<N>& h) noexcept {
    static_assert(N >= 2);
    h.size = 0;
    push(h, p.lo);
    finish(h, p.hi);
  }

 private:
  // TwoProduct is exact when a·b == 0 or |a·b| ≥ 2^-969; |a ⊗ b| ≥ 2^-968 implies the latter
  // (bounds::exact_product_threshold).
  void note_product(double a, double b, double p) noexcept {
    const bool exact = (p == 0) ? (a == 0 || b == 0) : (std::fabs(p) >= bounds::exact_product_threshold);
    exact_ &= exact && std::isfinite(p);
  }

  template <std::size_t N>
  static void push(Expansion<N>& h, double x) noexcept {
    if (x != 0) h.component[h.size++] = x;  // NaN is kept, so that check_finite sees it
  }
  template <std::size_t N>
  static void finish(Expansion<N>& h, double q) noexcept {
    if (q != 0 || h.size == 0) h.component[h.size++] = q;
  }

  bool exact_ = true;
};

// expansion_tail_enclosure: an enclosure (hi, lo, E) of the exact sum of an expansion: one TwoSum pass
// condenses it into Q plus small residuals r_j, then lo = Σ r_j rounded and E bounds that rounding.
//   Error bound: |S − (hi + lo)| ≤ (A ⊗ 2^-48) ⊕ 2μ, A = Σ|r_j| rounded (error_bounds.hpp, stage 3).
//   Certified by: proofs/plane/PlaneCompensated.v, `tail_sum_enclosure`.
template <std::size_t N>
[[nodiscard]] Enclosure expansion_tail_enclosure(const Expansion<N>& e) noexcept {
  static_assert(N <= bounds::tail_sum_max_terms);
  double q = e.component[0];
  double lo = 0, magnitude = 0;
  for (std::size_t i = 1; i < e.size; ++i) {
    const DoubleDouble s = two_sum(q, e.component[i]);
    q = s.hi;
    lo += s.lo;
    magnitude += std::fabs(s.lo);
  }
  return {q, lo, plus_absolute(magnitude * bounds::tail_sum_relative, absolute_constant(bounds::tail_sum_absolute))};
}

}  // namespace raykernel::detail
