// One ray–plane query through the certified cascade: its state, built once, and every stage that reads it.
//
//   den = d·n,   num = (p − o)·n                                        (docs/contract.md §1)
//
// RayPlaneTermsT holds what every stage starts from — the inputs, the differences p_i ⊖ o_i and stage 1's
// rounded dot products — for one query (V = double) or for four or eight at once (V = Lanes4, Lanes8: the
// batch API). The stages read it and never recompute it (the exact TwoDiff errors of the differences,
// which only stage 2 needs, are derived there from the same inputs and differences):
//
//   stage 1   den_filter_sign, num_filter_sign      dot3_filter_lanes          (certified/dot3_filter.hpp)
//   stage 2   den_compensated, num_compensated      compensated_dot3(_exact)   (certified/dot3_compensated.hpp)
//             den_refined, num_refined              compensated_dot3_refined, the second level
//   stage 3   ray_plane_expansions                  exact expansions           (certified/expansion.hpp)
//   t         round_quotient on an enclosure pair   (certified/quotient_rounding.hpp)
//
// `fast_answer` is the fast path `intersect` and the batch API run on raw input: stage 1, stage 2's first
// level and round_quotient, branch-free. `fast_relation` is stage 1 alone, for `relation`. Neither needs
// validated input: a certified nonzero sign of den implies d ≠ 0 and n ≠ 0 (a zero vector makes every
// product of den exactly 0), and a certified decision implies finite inputs (a NaN or infinite component
// makes the magnitude m, hence every bound compared against, NaN or +inf, and every certifying comparison
// false). Queries they leave uncertain are validated and continue in RayPlaneCascade from the same terms.
#pragma once

#include "certified/dot3_compensated.hpp"
#include "certified/dot3_filter.hpp"
#include "certified/eft.hpp"
#include "certified/enclosure.hpp"
#include "certified/error_bounds.hpp"
#include "certified/expansion.hpp"
#include "certified/lanes.hpp"
#include "certified/quotient_rounding.hpp"
#include "certified/sign.hpp"
#include "ray_plane_formula.hpp"

#include <raykernel/raykernel.hpp>

#include <optional>
#include <utility>

namespace raykernel::detail {

template <class V>
struct RayPlaneTermsT {
  V o[3], d[3], p[3], n[3];
  V diff[3];  // p_i ⊖ o_i, the a_i of num
  Dot3RoundedT<V> den, num;
};
using RayPlaneTerms = RayPlaneTermsT<double>;

template <class V>
[[nodiscard]] [[gnu::always_inline]] inline RayPlaneTermsT<V> ray_plane_terms(const V o[3], const V d[3], const V p[3],
                                                                              const V n[3]) noexcept {
  RayPlaneTermsT<V> q;
  for (int i = 0; i < 3; ++i) {
    q.o[i] = o[i], q.d[i] = d[i], q.p[i] = p[i], q.n[i] = n[i];
    q.diff[i] = p[i] - o[i];
  }
  q.den = dot3_rounded(q.d, q.n);
  q.num = dot3_rounded(q.diff, q.n);
  return q;
}

// The exact errors of the differences: p_i − o_i = diff_i + low_i (TwoDiff; its first operation is the
// p_i ⊖ o_i of the terms, so this is the same computation as two_diff(p_i, o_i)).
template <class V>
[[gnu::always_inline]] inline void difference_low_parts(const RayPlaneTermsT<V>& q, V low[3]) noexcept {
  for (int i = 0; i < 3; ++i) low[i] = two_diff(q.p[i], q.o[i]).lo;
}

// Calls f(o, d, p, n) with the query's vectors as the arrays the stages take.
template <class F>
[[gnu::always_inline]] inline decltype(auto) with_query_arrays(const Ray& ray, const Plane& plane, F f) noexcept {
  const Vec3 &ro = ray.origin, &rd = ray.direction, &pp = plane.point, &pn = plane.normal;
  const double o[3] = {ro.x, ro.y, ro.z}, d[3] = {rd.x, rd.y, rd.z};
  const double p[3] = {pp.x, pp.y, pp.z}, n[3] = {pn.x, pn.y, pn.z};
  return f(o, d, p, n);
}

[[nodiscard]] [[gnu::always_inline]] inline RayPlaneTerms ray_plane_terms(const Ray& ray, const Plane& plane) noexcept {
  return with_query_arrays(ray, plane, [](const double* o, const double* d, const double* p, const double* n) {
    return ray_plane_terms(o, d, p, n);
  });
}

// Stage 1 (never certifies zero: see RayPlaneCascade for the exactly-zero cases).
template <class V>
[[nodiscard]] [[gnu::always_inline]] inline IntegerOf<V> den_filter_sign(const RayPlaneTermsT<V>& q) noexcept {
  return dot3_filter_lanes(q.den, bounds::filter_den_relative);
}
template <class V>
[[nodiscard]] [[gnu::always_inline]] inline IntegerOf<V> num_filter_sign(const RayPlaneTermsT<V>& q) noexcept {
  return dot3_filter_lanes(q.num, bounds::filter_num_relative);
}

// Stage 2, first level.
template <class V>
[[nodiscard]] [[gnu::always_inline]] inline EnclosureT<V> den_compensated(const RayPlaneTermsT<V>& q) noexcept {
  return compensated_dot3_exact(q.d, q.n, q.den);
}
template <class V>
[[nodiscard]] [[gnu::always_inline]] inline EnclosureT<V> num_compensated(const RayPlaneTermsT<V>& q) noexcept {
  V low[3];
  difference_low_parts(q, low);
  return compensated_dot3(q.diff, low, q.n, q.num);
}

// Stage 2, second level (one query).
inline constexpr double exact_low_parts[3] = {0, 0, 0};  // den's inputs are exact: α = 0
[[nodiscard]] inline Enclosure den_refined(const RayPlaneTerms& q) noexcept {
  return compensated_dot3_refined(q.d, exact_low_parts, q.n, q.den);
}
[[nodiscard]] inline Enclosure num_refined(const RayPlaneTerms& q) noexcept {
  double low[3];
  difference_low_parts(q, low);
  return compensated_dot3_refined(q.diff, low, q.n, q.num);
}

// Stage 3: the exact expansions of num and den. num = Σ (δ_i + ε_i)·n_i with δ_i + ε_i = p_i − o_i exactly
// (the TwoDiff pair): each term is a 2-component expansion scaled by n_i (≤ 4 components), three ≤ 12.
struct ExactExpansions {
  Expansion<12> num;
  Expansion<6> den;
  bool exact;  // every TwoProduct was exact and nothing overflowed: num and den are the exact values
};
[[nodiscard]] inline ExactExpansions ray_plane_expansions(const RayPlaneTerms& q) noexcept {
  ExpansionBuilder builder;
  ExactExpansions e;
  {
    Expansion<2> product[3];
    for (int i = 0; i < 3; ++i) ExpansionBuilder::from_pair(builder.product(q.d[i], q.n[i]), product[i]);
    Expansion<4> partial;
    ExpansionBuilder::sum(product[0], product[1], partial);
    ExpansionBuilder::sum(partial, product[2], e.den);
  }
  {
    double low[3];
    difference_low_parts(q, low);
    Expansion<4> term[3];
    for (int i = 0; i < 3; ++i) {
      Expansion<2> difference;
      ExpansionBuilder::from_pair({q.diff[i], low[i]}, difference);
      builder.scale(difference, q.n[i], term[i]);
    }
    Expansion<8> partial;
    ExpansionBuilder::sum(term[0], term[1], partial);
    ExpansionBuilder::sum(partial, term[2], e.num);
  }
  builder.check_finite(e.num);
  builder.check_finite(e.den);
  e.exact = builder.exact();
  return e;
}

// ---------------------------------------------------------------------------------------------------------
// The fast paths.

// The fast path's answer, per query or per lane. `behind` and `t` are meaningful where `certain`.
template <class V>
struct FastAnswerT {
  V t;
  MaskOf<V> behind;              // the relation is behind, else hit
  MaskOf<V> certain;             // both signs certified nonzero (so the input is valid) and t certified
  MaskOf<V> relation_by_filter;  // stage 1 decided both signs (else the first compensated level helped)
};
using FastAnswer = FastAnswerT<double>;

// Stage 1, then the first level of stage 2 for the signs stage 1 left open, and round_quotient on the
// stage-2 enclosures for t.
//   Certified by: proofs/Cascade.v, `fast_answer_correct` (and `fast_path_den_valid` for validity).
template <class V>
[[nodiscard]] [[gnu::always_inline]] inline FastAnswerT<V> fast_answer(const RayPlaneTermsT<V>& q) noexcept {
  const IntegerOf<V> den_filter = den_filter_sign(q);
  const IntegerOf<V> num_filter = num_filter_sign(q);
  const EnclosureT<V> den = den_compensated(q);
  const EnclosureT<V> num = num_compensated(q);
  const IntegerOf<V> den_sign = first_certain_lanes(den_filter, enclosure_sign_lanes(den));
  const IntegerOf<V> num_sign = first_certain_lanes(num_filter, enclosure_sign_lanes(num));
  const QuotientRoundingT<V> t = round_quotient(num, prepare_divisor(den));
  return {t.t, signs_say_behind(num_sign, den_sign),
          both(both(den_sign != uncertain_lane, num_sign != uncertain_lane), t.certain),
          both(den_filter != uncertain_lane, num_filter != uncertain_lane)};
}

// Stage 1 alone, for the relation without t.
//   Certified by: proofs/Cascade.v, `fast_relation_correct` (which includes d ≠ 0 and n ≠ 0).
template <class V>
struct FastRelationT {
  MaskOf<V> behind;   // the relation is behind, else hit
  MaskOf<V> certain;  // both signs certified nonzero (so the input is valid)
};
// Written with |s| > B instead of dot3_filter_lanes' (s > B, s < −B): the same decision (B ≥ 0; NaN
// fails both), and then num·den < 0 exactly when the rounded values differ in sign. It computes only the
// stage-1 values it needs, as locals (GCC keeps them in registers; through RayPlaneTermsT it spills).
template <class V>
[[nodiscard]] [[gnu::always_inline]] inline FastRelationT<V> fast_relation(const V o[3], const V d[3], const V p[3],
                                                                           const V n[3]) noexcept {
  const V diff[3] = {p[0] - o[0], p[1] - o[1], p[2] - o[2]};
  const Dot3RoundedT<V> den = dot3_rounded(d, n);
  const Dot3RoundedT<V> num = dot3_rounded(diff, n);
  const V den_bound = dot3_filter_bound(den, bounds::filter_den_relative);
  const V num_bound = dot3_filter_bound(num, bounds::filter_num_relative);
  return {(num.value < 0) != (den.value < 0), both(abs(den.value) > den_bound, abs(num.value) > num_bound)};
}
template <class V>
[[nodiscard]] [[gnu::always_inline]] inline FastRelationT<V> fast_relation(const RayPlaneTermsT<V>& q) noexcept {
  return fast_relation(q.o, q.d, q.p, q.n);
}

// ---------------------------------------------------------------------------------------------------------
// The full cascade, for one valid query: the terms of the fast path, and stages 2 and 3 once asked for.

class RayPlaneCascade {
 public:
  RayPlaneCascade(const Ray& ray, const Plane& plane) noexcept : RayPlaneCascade(ray, plane, ray_plane_terms(ray, plane)) {}
  RayPlaneCascade(const Ray& ray, const Plane& plane, const RayPlaneTerms& terms) noexcept
      : ray_(ray), plane_(plane), q_(terms) {}

  [[nodiscard]] const Ray& ray() const noexcept { return ray_; }
  [[nodiscard]] const Plane& plane() const noexcept { return plane_; }
  [[nodiscard]] const RayPlaneTerms& terms() const noexcept { return q_; }

  // Stage 1, with the one way it certifies zero: every term has a zero factor, so the exact sum is 0
  // whatever the rounding.
  [[nodiscard]] Sign den_filter() const noexcept {
    const bool zero = (q_.d[0] == 0 || q_.n[0] == 0) && (q_.d[1] == 0 || q_.n[1] == 0) && (q_.d[2] == 0 || q_.n[2] == 0);
    return zero ? Sign::zero : static_cast<Sign>(den_filter_sign(q_));
  }
  [[nodiscard]] Sign num_filter() const noexcept {
    // p_i ⊖ o_i is 0 exactly when p_i = o_i (gradual underflow): then the term's exact value is 0.
    const bool zero = (q_.diff[0] == 0 || q_.n[0] == 0) && (q_.diff[1] == 0 || q_.n[1] == 0) &&
                      (q_.diff[2] == 0 || q_.n[2] == 0);
    return zero ? Sign::zero : static_cast<Sign>(num_filter_sign(q_));
  }

  [[nodiscard]] const Enclosure& den_compensated() noexcept { return once(den2_, [&] { return detail::den_compensated(q_); }); }
  [[nodiscard]] const Enclosure& num_compensated() noexcept { return once(num2_, [&] { return detail::num_compensated(q_); }); }
  [[nodiscard]] const Enclosure& den_refined() noexcept { return once(den2r_, [&] { return detail::den_refined(q_); }); }
  [[nodiscard]] const Enclosure& num_refined() noexcept { return once(num2r_, [&] { return detail::num_refined(q_); }); }
  [[nodiscard]] const ExactExpansions& expansions() noexcept { return once(exp3_, [&] { return ray_plane_expansions(q_); }); }

 private:
  template <class T, class F>
  static const T& once(std::optional<T>& slot, F compute) noexcept {
    if (!slot) slot = compute();
    return *slot;
  }

  Ray ray_;
  Plane plane_;
  RayPlaneTerms q_;
  std::optional<Enclosure> den2_, num2_, den2r_, num2r_;
  std::optional<ExactExpansions> exp3_;
};

// The functions below are multiversioned (certified/multiversion.hpp) and noexcept: an exception must not
// pass through a target_clones function, whose callers GCC 12 compiles without cleanups.

// The exact signs of num and den, and the stage that certified the later of the two.
struct CertifiedSigns {
  Sign num;  // never `uncertain`
  Sign den;  // never `uncertain`
  Stage stage;
};

// Stages 1–3 of the relation: the signs of num and den, each stage asked only for the signs the cheaper
// ones left uncertain, then the exact stage (exact/exact.hpp) when stage 3 is not exact (a TwoProduct
// underflowed or a value overflowed).
//   Certified by: proofs/Cascade.v, `cascade_signs_correct` (stages 1 and 2), Shewchuk's Theorems 13 and 19
//   (stage 3, proofs/README.md "Cited").
[[nodiscard]] CertifiedSigns certified_signs(RayPlaneCascade& query) noexcept;

// t = RN(num/den) for num ≠ 0 ≠ den (hit or behind): round_quotient on the stage-2 enclosures, on the
// second level's, on the stage-3 tail enclosures, then the exact stage. Returns t and the stage that
// rounded it.
//   Certified by: proofs/Cascade.v, `cascade_quotient_correct`, `expansion_t_correct`.
[[nodiscard]] std::pair<double, Stage> certified_quotient(RayPlaneCascade& query) noexcept;

// The whole cascade for a valid query (relation, then t), with the stages that decided them.
[[nodiscard]] TracedIntersection intersect_cascade(RayPlaneCascade& query) noexcept;

}  // namespace raykernel::detail
