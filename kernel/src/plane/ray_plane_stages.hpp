// One ray–plane query through the certified cascade: its state, built once, and every stage that reads it.
//
//   den = d·n,   num = (p − o)·n                                        (docs/contract.md §1)
//
// RayPlaneTermsT holds what every stage starts from — the inputs, the differences p_i ⊖ o_i and stage 1's
// rounded dot products — for one query (V = double) or for four or eight at once (V = Lanes4, Lanes8: the
// batch API). The stages read it and never recompute it (the exact TwoDiff errors of the differences,
// which only stage 2 needs, are derived there from the same inputs and differences):
//
//   stage 1   den_filter_sign, num_filter_sign      dot3_filter_lanes          (core/dot3_filter.hpp)
//   stage 2   den_compensated, num_compensated      compensated_dot3(_exact)   (core/dot3_compensated.hpp)
//             den_refined, num_refined              compensated_dot3_refined, the second level
//             compensated_pair, refined_pair        each level for den and num at once (RayPlanePair:
//                                                   the two lanes of a Lanes2, the same bits; the cascade's)
//   stage 3   ray_plane_expansions                  exact expansions           (core/expansion.hpp)
//   t         round_quotient on an enclosure pair   (core/quotient_rounding.hpp)
//
// `fast_answer` is the fast path `intersect` and the batch API run on raw input: stage 1, stage 2's first
// level and round_quotient, branch-free (`intersect` runs it in two steps, fast_stage1 and
// fast_answer_after_stage1, and leaves after the first when stage 1 leaves a sign open; then stage 2's second
// level from stage 1, refined_pair and filter_or_refined_signs, also on raw input: plane_api.cpp).
// `fast_relation` is stage 1 alone, for `relation`. Neither needs
// validated input: a certified nonzero sign of den implies d ≠ 0 and n ≠ 0 (a zero vector makes every
// product of den exactly 0), and a certified decision implies finite inputs (a NaN or infinite component
// makes the magnitude m, hence every bound compared against, NaN or +inf, and every certifying comparison
// false). Queries they leave uncertain are validated and continue in RayPlaneCascade
// (plane/ray_plane_cascade.hpp) from the same terms.
#pragma once

#include "core/dot3_compensated.hpp"
#include "core/dot3_filter.hpp"
#include "core/eft.hpp"
#include "core/enclosure.hpp"
#include "core/error_bounds.hpp"
#include "core/expansion.hpp"
#include "core/lanes.hpp"
#include "core/quotient_rounding.hpp"
#include "core/sign.hpp"
#include "plane/ray_plane_formula.hpp"

#include <raykernel/raykernel.hpp>


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

// The query's vectors as the arrays the stages take.
#define RAYKERNEL_QUERY_ARRAYS(ray, plane)                                                                  \
  const double o[3] = {(ray).origin.x, (ray).origin.y, (ray).origin.z};                                    \
  const double d[3] = {(ray).direction.x, (ray).direction.y, (ray).direction.z};                           \
  const double p[3] = {(plane).point.x, (plane).point.y, (plane).point.z};                                 \
  const double n[3] = {(plane).normal.x, (plane).normal.y, (plane).normal.z}

[[nodiscard]] [[gnu::always_inline]] inline RayPlaneTerms ray_plane_terms(const Ray& ray, const Plane& plane) noexcept {
  RAYKERNEL_QUERY_ARRAYS(ray, plane);
  return ray_plane_terms(o, d, p, n);
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

// ---------------------------------------------------------------------------------------------------------
// den and num of one query side by side, as the two lanes of a Lanes2: lane 0 den = Σ d_i n_i from
// a_i = d_i ⊖ 0 = d_i (whose TwoDiff error α_i is +0: the α = 0 form), lane 1 num = Σ (p_i − o_i) n_i from
// a_i = p_i ⊖ o_i with its TwoDiff error — each lane the very operations of the scalar stage for its value,
// with its own filter constant, so every value below is the scalar stage's bit for bit and every theorem
// about the stages holds lane by lane (proofs/README.md, "Lanes"). For den's first level the scalar stage
// is compensated_dot3_exact (g_i = l_i), the lane computes g_i = RN(0·n_i + l_i): the same bits, as
// l_i = RN(d_i n_i − (d_i ⊗ n_i)) is never −0 in round to nearest (an exact zero difference of two opposite
// values, or of ±0 and ∓0, is +0). tests/plane_stages_test.cpp compares every lane with the scalar stage.
// Half the instructions of two scalar evaluations: the fast path and the cascade's levels use it.
struct RayPlanePair {
  Lanes2 a[3], alpha[3], b[3];
  Dot3RoundedT<Lanes2> stage1;  // {den, num}
};

// The pair's operands from the inputs, into the caller's arrays (any bit pattern; α's lane 0 is +0 for every
// finite d_i). The fast path calls it on local arrays, which GCC keeps in registers (through a RayPlanePair
// it stores them: +31 instructions a query, measured).
[[gnu::always_inline]] inline void ray_plane_pair_operands(const double o[3], const double d[3], const double p[3],
                                                           const double n[3], Lanes2 a[3], Lanes2 alpha[3],
                                                           Lanes2 b[3]) noexcept {
  for (int i = 0; i < 3; ++i) {
    const DD<Lanes2> s = two_diff(Lanes2{d[i], p[i]}, Lanes2{0.0, o[i]});
    a[i] = s.hi;
    alpha[i] = s.lo;
    b[i] = Lanes2{n[i], n[i]};
  }
}

// From the inputs.
[[nodiscard]] [[gnu::always_inline]] inline RayPlanePair ray_plane_pair(const double o[3], const double d[3],
                                                                      const double p[3], const double n[3]) noexcept {
  RayPlanePair r;
  ray_plane_pair_operands(o, d, p, n, r.a, r.alpha, r.b);
  r.stage1 = dot3_rounded(r.a, r.b);
  return r;
}

// From a valid query's terms (the cascade: the same values, stage 1 not recomputed).
[[nodiscard]] inline RayPlanePair ray_plane_pair(const RayPlaneTerms& q) noexcept {
  RayPlanePair r;
  double low[3];
  difference_low_parts(q, low);
  for (int i = 0; i < 3; ++i) {
    r.a[i] = Lanes2{q.d[i], q.diff[i]};
    r.alpha[i] = Lanes2{0.0, low[i]};
    r.b[i] = Lanes2{q.n[i], q.n[i]};
    r.stage1.product[i] = Lanes2{q.den.product[i], q.num.product[i]};
  }
  r.stage1.value = Lanes2{q.den.value, q.num.value};
  r.stage1.magnitude = Lanes2{q.den.magnitude, q.num.magnitude};
  return r;
}

// Lane k of a pair's enclosures (0: den, 1: num).
[[nodiscard]] [[gnu::always_inline]] inline Enclosure enclosure_lane(const EnclosureT<Lanes2>& e, int k) noexcept {
  return {e.hi[k], e.lo[k], e.radius[k]};
}

// Stage 2's first level of den and num (den_compensated, num_compensated), and its second level (den_refined,
// num_refined), at once.
[[nodiscard]] [[gnu::always_inline]] inline EnclosureT<Lanes2> compensated_pair(const RayPlanePair& r) noexcept {
  return compensated_dot3(r.a, r.alpha, r.b, r.stage1);
}
[[nodiscard]] inline EnclosureT<Lanes2> refined_pair(const RayPlanePair& r) noexcept {
  return compensated_dot3_refined(r.a, r.alpha, r.b, r.stage1);
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
  MaskOf<V> rounding_certain;    // round_quotient on stage 2's first level was certain (t is RN(num/den) there)
};
using FastAnswer = FastAnswerT<double>;

// The fast path's decision from stage 1's signs and stage 2's enclosures: the signs stage 1 left open taken
// from the enclosures, t from round_quotient on them.
template <class V>
[[nodiscard]] [[gnu::always_inline]] inline FastAnswerT<V> fast_answer_from(IntegerOf<V> den_filter, IntegerOf<V> num_filter,
                                                                          const EnclosureT<V>& den,
                                                                          const EnclosureT<V>& num) noexcept {
  const IntegerOf<V> den_sign = first_certain_lanes(den_filter, enclosure_sign_lanes(den));
  const IntegerOf<V> num_sign = first_certain_lanes(num_filter, enclosure_sign_lanes(num));
  const QuotientRoundingT<V> t = round_quotient(num, prepare_divisor(den));
  return {t.t, signs_say_behind(num_sign, den_sign),
          both(both(den_sign != uncertain_lane, num_sign != uncertain_lane), t.certain),
          both(den_filter != uncertain_lane, num_filter != uncertain_lane), t.certain};
}

// Stage 1, then the first level of stage 2 for the signs stage 1 left open, and round_quotient on the
// stage-2 enclosures for t; per query, or per lane of a batch.
//   Certified by: proofs/plane/PlaneCascade.v, `fast_answer_correct` (and `fast_path_den_valid` for validity); on the
//   bits, any input pattern, proofs/plane/PlaneQueryTwins.v, `fast_answer_twin_correct`.
template <class V>
[[nodiscard]] [[gnu::always_inline]] inline FastAnswerT<V> fast_answer(const RayPlaneTermsT<V>& q) noexcept {
  return fast_answer_from(den_filter_sign(q), num_filter_sign(q), den_compensated(q), num_compensated(q));
}

// What the one-query fast path computed and the cascade continues from when it certifies nothing: the
// differences p_i ⊖ o_i (lane 1 of RayPlanePair's a_i), stage 1 of den and num, and stage 2's first level
// of both — the same operations on the same bits as the cascade's own evaluation (RayPlanePair), so handing them
// over changes no value (tests/plane_stages_test.cpp compares them).
struct RayPlaneFastValues {
  Lanes2 a[3];
  Dot3RoundedT<Lanes2> stage1;
  EnclosureT<Lanes2> compensated;
};

// The same for one query, with den and num computed side by side as the two lanes of a Lanes2 (RayPlanePair's
// operations, on local arrays); `values` receives what the cascade continues from. In two steps, so that
// `intersect` can leave after the first when stage 1 certifies neither sign or only one (plane_api.cpp):
// fast_stage1, the pair's operands and stage 1 with its signs (the filter's per lane), then
// fast_answer_after_stage1, stage 2's first level and fast_answer_from.
[[nodiscard]] [[gnu::always_inline]] inline Mask2 fast_stage1(const double o[3], const double d[3], const double p[3],
                                                            const double n[3], RayPlaneFastValues& values,
                                                            Lanes2 alpha[3], Lanes2 b[3]) noexcept {
  ray_plane_pair_operands(o, d, p, n, values.a, alpha, b);
  values.stage1 = dot3_rounded(values.a, b);
  return dot3_filter_lanes(values.stage1, Lanes2{bounds::filter_den_relative, bounds::filter_num_relative});
}
[[nodiscard]] [[gnu::always_inline]] inline FastAnswer fast_answer_after_stage1(Mask2 filter, const Lanes2 alpha[3],
                                                                             const Lanes2 b[3],
                                                                             RayPlaneFastValues& values) noexcept {
  values.compensated = compensated_dot3(values.a, alpha, b, values.stage1);
  return fast_answer_from<double>(filter[0], filter[1], enclosure_lane(values.compensated, 0),
                                  enclosure_lane(values.compensated, 1));
}
[[nodiscard]] [[gnu::always_inline]] inline FastAnswer fast_answer(const double o[3], const double d[3], const double p[3],
                                                                const double n[3], RayPlaneFastValues& values) noexcept {
  Lanes2 alpha[3], b[3];
  const Mask2 filter = fast_stage1(o, d, p, n, values, alpha, b);
  return fast_answer_after_stage1(filter, alpha, b, values);
}
[[nodiscard]] [[gnu::always_inline]] inline FastAnswer fast_answer(const double o[3], const double d[3], const double p[3],
                                                                const double n[3]) noexcept {
  RayPlaneFastValues values;
  return fast_answer(o, d, p, n, values);
}
[[nodiscard]] [[gnu::always_inline]] inline FastAnswer fast_answer(const Ray& ray, const Plane& plane,
                                                                RayPlaneFastValues& values) noexcept {
  RAYKERNEL_QUERY_ARRAYS(ray, plane);
  return fast_answer(o, d, p, n, values);
}
[[nodiscard]] [[gnu::always_inline]] inline FastAnswer fast_answer(const Ray& ray, const Plane& plane) noexcept {
  RayPlaneFastValues values;
  return fast_answer(ray, plane, values);
}

// Stage 2's second level of den and num from the fast path's stage 1, with the pair's operands from the inputs
// (ray_plane_pair_operands: for a valid query, the a_i the fast path used and the α the cascade gives that level,
// +0 in den's lane): the cascade's refined_pair bit for bit, without building the cascade.
[[nodiscard]] [[gnu::always_inline]] inline EnclosureT<Lanes2> refined_pair(const Dot3RoundedT<Lanes2>& stage1, const Ray& ray,
                                                                         const Plane& plane) noexcept {
  RAYKERNEL_QUERY_ARRAYS(ray, plane);
  RayPlanePair r;
  ray_plane_pair_operands(o, d, p, n, r.a, r.alpha, r.b);
  r.stage1 = stage1;
  return refined_pair(r);
}

// The signs of den and num (lanes 0 and 1) from stage 1's filter where it is certain, else from stage 2's second
// level (neither certifies zero, so a certain sign is ±1).
[[nodiscard]] [[gnu::always_inline]] inline Mask2 filter_or_refined_signs(Mask2 filter,
                                                                       const EnclosureT<Lanes2>& refined) noexcept {
  return first_certain_lanes(filter, enclosure_sign_lanes(refined));
}

// Stage 1 alone, for the relation without t.
//   Certified by: proofs/plane/PlaneCascade.v, `fast_relation_correct` (which includes d ≠ 0 and n ≠ 0); on the bits,
//   any input pattern, proofs/plane/PlaneQueryTwins.v, `fast_relation_twin_correct`.
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
// For one query, den and num side by side as the two lanes of a Lanes2 (as fast_answer does; the den lane's
// a_i = d_i ⊖ 0 = d_i exactly).
[[nodiscard]] [[gnu::always_inline]] inline FastRelationT<double> fast_relation(const Ray& ray, const Plane& plane) noexcept {
  RAYKERNEL_QUERY_ARRAYS(ray, plane);
  Lanes2 a[3], b[3];
  for (int i = 0; i < 3; ++i) {
    a[i] = Lanes2{d[i], p[i]} - Lanes2{0.0, o[i]};
    b[i] = Lanes2{n[i], n[i]};
  }
  const Dot3RoundedT<Lanes2> stage1 = dot3_rounded(a, b);
  const Lanes2 bound = dot3_filter_bound(stage1, Lanes2{bounds::filter_den_relative, bounds::filter_num_relative});
  const Mask2 certain = abs(stage1.value) > bound;
  return {(stage1.value[1] < 0) != (stage1.value[0] < 0), static_cast<bool>(certain[0] & certain[1])};
}

}  // namespace raykernel::detail
