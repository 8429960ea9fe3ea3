// The nearest-hit module: one search over every kind of surface (planes, the triangles of a mesh, spheres),
// nearest/nearest_search.hpp, on the candidates defined here and in plane_candidate.hpp, triangle_candidate.hpp and
// sphere_candidate.hpp.
//
// A candidate is a surface whose relation to the ray is hit, with what its relation was decided from, kept
// for as long as it may win: its kind (SurfaceKind, the order of exact ties between kinds), its index within
// its kind, and what orders its t against the others'.
//
// The quotient kinds (planes, triangles: t = num/den) keep the exact signs of num and den (den ≠ 0; num zero —
// t = 0 — or with den's sign), the stage that certified them, and the stages of their exact t, each computed the
// first time a comparison or the rounding asks for it and then kept:
//
//   stage 1  num_filter(), den_filter()              RoundedEnclosure: the relation's own stage-1 values
//   stage 2  num_compensated(), den_compensated()    Enclosure (double-double)
//   stage 3  expansions()                            .exact, .num, .den: exact expansions (≤ 16 components)
//   stage 4  exact_order(ray, a, b)                  rationals (nearest/exact_nearest.hpp)
//
// and round_t(): RN(t) once, for the winner (or for the BVH walk's pruning bound, then reused), with the stage
// that rounded it. Two candidates of any two quotient kinds are ordered by compare_candidates: t = 0 first,
// then sign(t_a − t_b) = sign(Δ)·sign(den_a)·sign(den_b), Δ = num_a·den_b − num_b·den_a, by
// compare_quotients_filter, [a kind pair's shortcut without arithmetic], compare_quotients_compensated,
// compare_quotients_expansion (nearest/compare_quotients.hpp, each proved for any enclosures or expansions of
// the four values) and the exact stage, each asked only when the cheaper ones cannot decide. Two quotients are
// never ordered by their rounded t.
//
// A sphere's t is a root U ∓ √V, not a quotient (sphere_candidate.hpp): its cascade rounds it correctly with the
// relation, and a pair with a sphere in it is ordered by the two correctly rounded t when they differ (RN is
// monotone: proofs/core/RoundOrder.v, `rn_strict_order`), otherwise in rationals (exact_order overloads). The
// search dispatches on the pair of kinds; the best-so-far bookkeeping, the tie rule, the pruning bound, the
// tracing and the rounding of the winner are written once, in the search.
#pragma once

#include "core/enclosure.hpp"
#include "core/escalation.hpp"
#include "core/sign.hpp"
#include "nearest/compare_quotients.hpp"

#include <raykernel/core.hpp>
#include <raykernel/nearest_scene.hpp>

#include <cstdint>

namespace raykernel::detail {

// The sign of t_a − t_b (−1, 0, +1), the cheapest stage that certified it, and whether an exact tie was
// recognized without arithmetic (both t = 0, or a kind pair's shortcut: triangles with one plane or one
// crossing point, triangle_candidate.hpp).
struct DistanceOrder {
  int sign;
  Stage stage;
  bool without_arithmetic = false;
};

// A kind pair's way to see an exact tie without arithmetic; none unless an overload says otherwise.
template <class A, class B>
[[nodiscard]] constexpr bool same_t_without_arithmetic(const A&, const B&) noexcept {
  return false;
}

// Stage 3 of the comparison, out of line: its products of expansions need kilobytes of stack, which the search's
// hot frame should not carry (nor probe page by page on every ray).
template <class A, class B>
[[nodiscard]] [[gnu::noinline]] std::optional<DistanceOrder> compare_candidates_by_expansions(A& a, B& b,
                                                                                              int orientation) noexcept {
  const auto& ea = a.expansions();
  const auto& eb = b.expansions();
  if (ea.exact && eb.exact) {
    const Sign delta = compare_quotients_expansion(ea.num, ea.den, eb.num, eb.den);
    if (is_certain(delta)) return DistanceOrder{orientation * static_cast<int>(delta), Stage::expansion};
  }
  return std::nullopt;
}

// Stages 1 to 3 of the comparison of two quotient candidates: the order, or nothing when the exact stage must
// decide. The filter stage reads the kept stage-1 values; the later stages are computed on first use and kept
// in the candidates.
template <class A, class B>
[[nodiscard]] [[gnu::always_inline]] inline std::optional<DistanceOrder> compare_candidates_certified(A& a, B& b) noexcept {
  // t = 0 exactly (num = 0) comes first; num's sign is exact.
  const bool a_at_origin = a.num_sign == Sign::zero, b_at_origin = b.num_sign == Sign::zero;
  if (a_at_origin || b_at_origin)
    return DistanceOrder{static_cast<int>(!a_at_origin) - static_cast<int>(!b_at_origin), Stage::filter,
                         a_at_origin && b_at_origin};

  // sign(t_a − t_b) = sign(Δ)·sign(den_a)·sign(den_b), Δ's sign through the stages (core/escalation.hpp).
  const int orientation = a.den_sign == b.den_sign ? 1 : -1;
  Escalation trace;
  bool tie_without_arithmetic = false;
  const Sign delta = trace.sign(
      // compare_quotients_filter, inlined (its lane form on one lane: the same operations).
      SignStage{Stage::filter,
                [&] {
                  return static_cast<Sign>(compare_quotients_filter_lanes(a.num_filter(), a.den_filter(),
                                                                          b.num_filter(), b.den_filter()));
                }},
      // A kind pair's exact tie seen without arithmetic counts as the filter.
      SignStage{Stage::filter,
                [&] {
                  tie_without_arithmetic = same_t_without_arithmetic(a, b);
                  return tie_without_arithmetic ? Sign::zero : Sign::uncertain;
                }},
      SignStage{Stage::compensated, [&] {
                  return enclosure_sign(compare_quotients_compensated(a.num_compensated(), a.den_compensated(),
                                                                      b.num_compensated(), b.den_compensated()));
                }});
  if (tie_without_arithmetic) return DistanceOrder{0, Stage::filter, true};
  if (is_certain(delta)) return DistanceOrder{orientation * static_cast<int>(delta), trace.reached()};
  return compare_candidates_by_expansions(a, b, orientation);
}

// The exact order of two candidates' t, the exact stage last (exact_order overloads: rationals).
template <class A, class B>
[[nodiscard]] inline DistanceOrder compare_candidates(const Ray& ray, A& a, B& b) {
  if (const std::optional<DistanceOrder> order = compare_candidates_certified(a, b)) return *order;
  return DistanceOrder{exact_order(ray, a, b), Stage::exact};
}

// Whether candidate a (of kind `a_kind`, index `a_index`) wins an exact tie with b: the kind first (a plane
// before a triangle), then the smaller index.
[[nodiscard]] constexpr bool wins_tie(SurfaceKind a_kind, std::size_t a_index, SurfaceKind b_kind,
                                      std::size_t b_index) noexcept {
  return a_kind != b_kind ? static_cast<int>(a_kind) < static_cast<int>(b_kind) : a_index < b_index;
}

}  // namespace raykernel::detail
