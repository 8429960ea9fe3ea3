// The ray–plane cascade beyond the fast path, for one valid query: the relation from the signs of num and
// den, each stage asked only for what the cheaper ones left open, and t rounded by the first stage whose
// enclosures certify it, then at the rounding boundaries of stage 3's candidate in the exact expansions (a t
// just above a power of two, or on a midpoint), then by the exact stage (plane/ray_plane_stages.hpp has the
// stages and the per-query state).
//   Certified by: proofs/plane/PlaneCascadeTwins.v, `certified_quotient_twin_sound` (every t certified_quotient
//   returns is RN(num/den), den ≠ 0; the boundary step by proofs/core/QuotientBoundary.v,
//   `round_quotient_near_sound`, with den's sign from `expansion_sign_sound`), `cascade_twin_correct`;
//   the control flow twinned there and run against this code by the differential runner (routines
//   cascade_intersect, cascade_relation).
//
// Compiled with -ffp-contract=off and without fast-math (kernel/CMakeLists.txt): the proofs model each
// + − × / as one correctly rounded operation and each std::fma as one rounding. Each function is cloned
// for CPUs with and without an FMA unit (core/multiversion.hpp); both clones compute the same bits.
#include "core/fp_requirements.hpp"
#include "core/escalation.hpp"
#include "core/multiversion.hpp"
#include "plane/ray_plane_cascade.hpp"
#include "plane/exact_plane.hpp"
#include "plane/exact_plane_compare.hpp"
#include "core/quotient_boundary.hpp"

#include <limits>

namespace raykernel::detail {

RAYKERNEL_MULTIVERSION_FLATTEN
CertifiedSigns certified_signs(RayPlaneCascade& query) noexcept {
  // Each sign through the stages (core/escalation.hpp): the binary64 filter, stage 2's two levels (the second
  // for values that cancel to within ~2^-100 of the terms), computed on demand and kept for the rounding of t,
  // then the exact expansions when they are exact.
  Escalation trace;
  const auto escalate = [&](bool den) {
    return trace.sign(
        SignStage{Stage::filter, [&] { return den ? query.den_filter() : query.num_filter(); }},
        SignStage{Stage::compensated, [&] { return enclosure_sign(den ? query.den_compensated() : query.num_compensated()); }},
        SignStage{Stage::compensated, [&] { return enclosure_sign(den ? query.den_refined() : query.num_refined()); }},
        SignStage{Stage::expansion, [&] {
          const ExactExpansions& e = query.expansions();
          return !e.exact ? Sign::uncertain : den ? e.den.sign() : e.num.sign();
        }});
  };
  const Sign den = escalate(true);  // den first, then num, on one trace (PlaneCascadeTwins.v's order)
  const Sign num = escalate(false);
  if (is_certain(den) && is_certain(num)) return {num, den, trace.reached()};
  // The exact stage, for both signs (one rational evaluation gives both).
  const exact::ExactSigns s = exact::ray_plane_signs(query.ray(), query.plane());
  return {sign_from_int(s.num), sign_from_int(s.den), Stage::exact};
}

RAYKERNEL_MULTIVERSION_FLATTEN
std::pair<double, Stage> certified_quotient(RayPlaneCascade& query) noexcept {
  // The first level's rounding: kept by the cascade (from the fast path, when it came from there).
  if (const QuotientRounding& r = query.compensated_rounding(); r.certain) return {r.t, Stage::compensated};
  if (const auto t = round_quotient_if_certain(query.num_refined(), prepare_divisor(query.den_refined())))
    return {*t, Stage::compensated};
  if (const ExactExpansions& e = query.expansions(); e.exact) {
    const QuotientRounding r =
        round_quotient(expansion_tail_enclosure(e.num), prepare_divisor(expansion_tail_enclosure(e.den)));
    if (r.certain) return {r.t, Stage::expansion};
    // The rounding boundaries of the candidate, exactly in the expansions (core/quotient_boundary.hpp).
    const Sign den_sign = e.den.sign();
    if (den_sign == Sign::positive || den_sign == Sign::negative) {
      if (const auto t = round_quotient_near(e.num, e.den, static_cast<int>(den_sign), r.t))
        return {*t, Stage::expansion};
    }
  }
  return {exact::intersect(query.ray(), query.plane()).t, Stage::exact};
}

TracedIntersection intersect_cascade(RayPlaneCascade& query) noexcept {
  const CertifiedSigns signs = certified_signs(query);
  const Relation relation = relation_from_signs(static_cast<int>(signs.num), static_cast<int>(signs.den));
  if (relation == Relation::parallel || relation == Relation::in_plane)
    return {{relation, std::numeric_limits<double>::quiet_NaN()}, signs.stage, signs.stage};
  if (signs.num == Sign::zero) return {{Relation::hit, 0.0}, signs.stage, signs.stage};  // t = 0 exactly: +0
  // Extreme exponents (stage 3 was not exact): the exact stage rounds t too.
  if (signs.stage == Stage::exact) return {exact::intersect(query.ray(), query.plane()), Stage::exact, Stage::exact};
  const auto [t, t_stage] = certified_quotient(query);
  return {{relation, t}, signs.stage, t_stage};
}

}  // namespace raykernel::detail
