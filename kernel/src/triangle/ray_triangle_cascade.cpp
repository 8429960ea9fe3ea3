// The certified ray–triangle cascade: filter → compensated → expansion → exact, for the signs of πa, πb, πc,
// den and num (and, when a π or den is exactly 0, the tie-break and degeneracy signs), and the correctly
// rounded quotients t = num/den and πk/den.
//
// The fast path evaluates stage 2 (whose high parts are stage 1's values) when something is to be rounded, or
// stage 1 alone for the relation, takes every sign from the filter or else from the enclosure, and when the
// signs of den and the three π are certain (then nonzero: the branch-free decisions never certify zero, and
// the input is valid, see below) decides the location directly: inside when all three have den's sign, else
// outside, and the owned rule agrees with the closed one (no π is 0). The quotients are rounded by
// round_quotient on the stage-2 enclosures, t and the three coordinates over one divisor prepared once from
// den's enclosure (one reciprocal). What the fast path does not certify, the caller validates and hands to the
// full cascade (ray_triangle_cascade.hpp), which escalates each sign and each quotient on its own.
//
// No validation is needed before the fast path: a certified sign of den implies finite inputs and d ≠ 0. Its
// magnitude m sums the permanents of all three π, so a NaN or infinite component anywhere (o and d reach every
// π; a vertex reaches two of the cross products) makes m, hence the bound and the radius, non-finite; and
// d = 0 makes every product of den exactly 0, which neither stage certifies as nonzero.
//
// Certified by:
//   signs, stage 1:      proofs/triangle/TriangleFilter.v, `pi_filter_sound`, `num_filter_sound`, `den_filter_sound`
//   signs, stage 2:      proofs/triangle/TriangleCompensated.v, `pi_compensated_encloses`, `den_compensated_encloses`
//                        proofs/triangle/TriangleCompensated.v, `num_compensated_encloses`
//                        proofs/plane/PlaneCompensated.v, `enclosure_sign_sound`
//   the fast path:       proofs/triangle/TriangleCascade.v, `triangle_fast_sign_correct`, `fast_location_correct`
//                        proofs/triangle/TriangleCascade.v, `den_nonzero_direction`
//                        proofs/triangle/TriangleCompensated.v, `stage2_filter_view`
//   quotients, stage 2:  proofs/triangle/TriangleCascade.v, `triangle_quotient_correct` (round_quotient_sound)
//   quotients, stage 3:  proofs/triangle/TriangleCascade.v, `triangle_quotient_expansion_correct`
//                        (tail_sum_enclosure) on stage 3's value of each determinant: its integer's at most
//                        four components when the leaves allow (proofs/triangle/TriangleIntegerSign.v,
//                        `integer_value_components_sound`), else its exact expansion of doubles; in the cascade
//                        proofs/triangle/TriangleCascadeFlowCorrect.v, `tc_stage3_components_sound`,
//                        `tc_stage3_sign_sound` (den's sign there); then at the rounding boundaries of the candidate, in the
//                        expansions: proofs/core/QuotientBoundary.v, `round_quotient_near_sound` (from
//                        `round_quotient_at_boundaries_sound`, for the candidate or a neighbour), in the
//                        cascade proofs/triangle/TriangleCascadeQuotients.v, `tc_qinv_boundary`, `tc_short_means`,
//                        `tc_den_sign_means`
//   the full cascade:    proofs/triangle/TriangleCascadeFlowCorrect.v, `tc_classify_b_correct`
//                        proofs/triangle/TriangleCascadeFlowCorrect.v, `tc_stage3_quotient_correct`
//                        proofs/triangle/TriangleCascadeQuotients.v, `tc_intersect_b_correct` (classification and every
//                        quotient of triangle_intersection_cascade's answer before the exact stage)
//                        proofs/triangle/TriangleIntersectPublic.v, `tc_intersect_b_den_nonzero` (a quotient with a value
//                        comes with den ≠ 0)
//                        (TriangleCascade's control flow twinned in TriangleCascadeFlowTwins.v and run against this
//                        code by the differential runner, routines tri_cascade_intersect, tri_cascade_relation)
//   decisions:           proofs/triangle/TriangleRule.v, `triangle_location_correct`, `owned_sign_nonzero`
//                        proofs/triangle/TriangleRule.v, `owned_sign_antisymmetric`
//   stage 3, integers:   proofs/triangle/TriangleIntegerSign.v, `integer_value_sign_sound` (a determinant whose
//                        leaves are integer vectors — d, and p − o from TwoDiff's two parts, `difference_vector_ok` —
//                        its sign in integers: proofs/core/IntegerDet3.v, `integer_det3_sign_correct`,
//                        `integer_vector_sum_value`; tried first, TriangleCascadeFlowTwins.v's tc_sign_b)
//   stage 3 values:      proofs/triangle/TriangleStage3Twins.v, `triangle_expansion_sign_sound`, `value_ev_exact`
//                        (the composition in expansion_value.hpp and ray_triangle_stages.hpp's value_expansion,
//                        twinned and run against the C++: routine tri_expansion); each sum and scale by
//                        proofs/core/Expansions.v, `sum_gen_exact`, `scale_gen_exact`; stage 4: GMP and MPFR.
//
// Compiled with -ffp-contract=off and without fast-math (kernel/CMakeLists.txt).
#include "triangle/ray_triangle_cascade.hpp"

#include "core/escalation.hpp"
#include "core/fp_requirements.hpp"
#include "core/multiversion.hpp"
#include "core/quotient_rounding.hpp"
#include "core/quotient_boundary.hpp"
#include "triangle/exact_triangle.hpp"
#include "triangle/ray_triangle_stages.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>

namespace raykernel::detail {
namespace {

constexpr double not_a_number = std::numeric_limits<double>::quiet_NaN();

// The values to round: t = num/den (index 0) and πa/den, πb/den, πc/den (indices 1–3), as determinant indices.
constexpr int numerator_value[4] = {value_num, value_pi_a, value_pi_b, value_pi_c};

// The four quotients in the fast path's lane order: RN(πa/den), RN(πb/den), RN(πc/den), RN(num/den).
struct FourQuotients {
  double t[4];
  bool certain[4];
};

// The one place where the fast path rounds: round_quotient of each numerator's enclosure (lanes πa, πb, πc,
// num) over one divisor prepared from den's enclosure — one reciprocal for all four — in one Lanes4 pass,
// four roundings per vector operation (each lane the scalar operations: proofs/triangle/TriangleCascade.v,
// `triangle_quotient_correct`, with the divisor shared).
[[gnu::always_inline]] inline FourQuotients round_quotients(const EnclosureT<Lanes4>& numerators,
                                                             const Enclosure& den) noexcept {
  const Divisor d = prepare_divisor(den);
  const DivisorT<Lanes4> shared{broadcast<Lanes4>(d.hi), broadcast<Lanes4>(d.lo), broadcast<Lanes4>(d.radius),
                                broadcast<Lanes4>(d.reciprocal), Mask4{} - static_cast<std::int64_t>(d.in_range)};
  const QuotientRoundingT<Lanes4> r = round_quotient(numerators, shared);
  FourQuotients q;
  for (int k = 0; k < 4; ++k) {
    q.t[k] = r.t[k];
    q.certain[k] = r.certain[k] != 0;
  }
  return q;
}

// The relative constants of the four lanes (π, π, π, num).
const Lanes4 filter_relative_lanes{bounds::triangle_filter_pi_relative, bounds::triangle_filter_pi_relative,
                                   bounds::triangle_filter_pi_relative, bounds::triangle_filter_num_relative};

// Numerator k of the quotients (t, ua, ub, uc) and its lane in the fast path's layout.
constexpr int numerator_lane[4] = {lane_num, value_pi_a, value_pi_b, value_pi_c};

TriangleIntersection answer(const TriangleClassification& c) noexcept {
  return {c.relation, c.location, c.owned, not_a_number, {not_a_number, not_a_number, not_a_number}};
}

// ---- The full cascade --------------------------------------------------------------------------------------

// One query in the full cascade: each sign escalated on its own, stage by stage, the stages computed once.
class TriangleCascade {
 public:
  // Stage 2 is evaluated at once, in lanes: the cascade runs when the fast path left a sign open, and stage 1's
  // values are its filter view (proofs/triangle/TriangleCompensated.v, `stage2_filter_view`).
  [[gnu::always_inline]] TriangleCascade(const Ray& ray, const Triangle& triangle)
      : ray_(ray), triangle_(triangle), compensated_(triangle_compensated_values_by_lanes(ray, triangle)),
        integer_leaves_(ray, triangle) {}
  // From the values the fast path left (the same evaluation: the same bits).
  [[gnu::always_inline]] TriangleCascade(const Ray& ray, const Triangle& triangle, const TriangleCompensatedValues& stage2)
      : ray_(ray), triangle_(triangle), compensated_(stage2), integer_leaves_(ray, triangle) {}

  // The classification through stage 3, or nothing when a sign needed the exact stage.
  std::optional<TriangleClassification> classify(TriangleRule rule) {
    const TriangleClassification c = classify_triangle(
        rule, [&] { return sign(value_den); }, [&](int k) { return sign(k); },
        [&](int k) { return tie_break(k); }, [&] { return sign(value_num); }, [&] { return normal_is_zero(); });
    if (needs_exact_) return std::nullopt;
    return c;
  }

  // The exact sign of determinant v (stages 1–3, core/escalation.hpp); sets needs_exact_ (and returns 0) when
  // no stage certifies it (stage 3 is not exact). Each determinant is escalated once per query: the roundings
  // ask again the signs the classification asked (a zero π of a ray through a vertex), and get the same answer
  // and the same trace (the trace is the latest stage asked, already recorded).
  int sign(int v) {
    const Sign s = sign_.get(static_cast<std::size_t>(v), [&] {
      return trace_.sign(SignStage{Stage::filter, [&] { return det3_filter_sign(v); }},
                         SignStage{Stage::compensated, [&] { return enclosure_sign(compensated().enclosure(v)); }},
                         SignStage{Stage::expansion, [&] { return stage3_sign(v); }});
    });
    if (!is_certain(s)) {
      needs_exact_ = true;
      return 0;
    }
    return static_cast<int>(s);
  }

  // Stage 3's sign of determinant v: in integers when its leaves allow (integer_value_sign: about a fifth of an
  // expansion's cost), else from its expansion.
  Sign stage3_sign(int v) {
    const Sign s = integer_value_sign(integer_leaves_, v);
    return is_certain(s) ? s : expansion(v).sign();
  }

  [[nodiscard]] Stage stage() const noexcept { return trace_.reached(); }
  // Records that the roundings asked `stage`; returns the query's trace.
  Stage reach(Stage stage) noexcept {
    trace_.reach(stage);
    return trace_.reached();
  }
  [[nodiscard]] bool needs_exact() const noexcept { return needs_exact_; }

  // Stage 3's enclosure of determinant v: expansion_tail_enclosure of its exact expansion (short_expansion),
  // when it has at most bounds::tail_sum_max_terms components (the range tail_sum_enclosure is proved for).
  // The integer's components are summed where they are (no copy into a capacity-32 expansion: the same
  // components, the same sums).
  std::optional<Enclosure> expansion_enclosure(int v) {
    const IntegerValue& integer = integer_value(v);
    if (integer.ok) return expansion_tail_enclosure(integer.e);
    const std::optional<Expansion<bounds::tail_sum_max_terms>> e = short_expansion<bounds::tail_sum_max_terms>(v);
    if (!e) return std::nullopt;
    return expansion_tail_enclosure(*e);
  }
  // Stage 3's exact value of determinant v for the roundings, in capacity K when it has at most K components
  // (16: the capacity round_quotient_near is proved for): from its integer when its leaves allow (at most four
  // components: integer_value_components), else its expansion of doubles when that is exact.
  template <std::size_t K>
  std::optional<Expansion<K>> short_expansion(int v) {
    const IntegerValue& integer = integer_value(v);
    if (integer.ok) return shortened<K>(integer.e);
    const ExpansionValue<192>& value = expansion(v);
    if (!value.exact) return std::nullopt;
    return shortened<K>(value.e);
  }
  // Stage 3's integer value of determinant v (integer_value_components), computed on first use.
  const IntegerValue& integer_value(int v) {
    return integer_value_.get(static_cast<std::size_t>(v), [&] { return integer_value_components(integer_leaves_, v); });
  }
  [[nodiscard]] const TriangleCompensatedValues& compensated() const noexcept { return compensated_; }
  // Stage 3 of determinant v, computed on first use.
  const ExpansionValue<192>& expansion(int v) {
    return expansion_.get(static_cast<std::size_t>(v), [&] { return value_expansion(ray_, triangle_, v); });
  }

 private:
  Sign det3_filter_sign(int v) {
    return static_cast<Sign>(det3_filter_lanes(filter_view(compensated_.value[static_cast<std::size_t>(v)]),
                                               filter_relative(v), compensated_.absolute(v)));
  }
  std::array<int, 3> tie_break(int k) {
    trace_.reach(Stage::expansion);
    if (const auto s = tie_break_signs_by_expansion(ray_, triangle_, k)) return *s;
    needs_exact_ = true;
    return {1, 0, 0};
  }
  bool normal_is_zero() {
    trace_.reach(Stage::expansion);
    if (const auto z = normal_is_zero_by_expansion(triangle_)) return *z;
    needs_exact_ = true;
    return false;
  }

  const Ray& ray_;
  const Triangle& triangle_;
  Escalation trace_;
  bool needs_exact_ = false;
  TriangleCompensatedValues compensated_;
  OnFirstUse<Sign, triangle_value_count> sign_;  // each determinant's sign, escalated once
  IntegerLeaves integer_leaves_;  // stage 3's integer vectors, each read once
  OnFirstUse<IntegerValue, triangle_value_count> integer_value_;  // stage 3's integer value of each determinant
  OnFirstUse<ExpansionValue<192>, triangle_value_count> expansion_;  // stage 3 of each determinant, once computed
};

// Four scalar enclosures (in lane order) as the lanes of one.
[[gnu::always_inline]] inline EnclosureT<Lanes4> enclosure_lanes(const Enclosure e[4]) noexcept {
  EnclosureT<Lanes4> n;
  for (int k = 0; k < 4; ++k) {
    n.hi[k] = e[k].hi;
    n.lo[k] = e[k].lo;
    n.radius[k] = e[k].radius;
  }
  return n;
}

// ---- The fast path -----------------------------------------------------------------------------------------

// The decision when den and the three π have certain (hence nonzero) signs: inside or outside, the same under
// both rules. `num_sign` is consulted only inside. Returns nothing when num's sign is needed and uncertain.
[[gnu::always_inline]] inline std::optional<TriangleClassification> decide_nonzero(std::int64_t sa, std::int64_t sb,
                                                                                   std::int64_t sc, std::int64_t sden,
                                                                                   std::int64_t snum) noexcept {
  const bool inside = (sa == sden) & (sb == sden) & (sc == sden);
  if (!inside) return TriangleClassification{TriangleRelation::miss, TriangleLocation::outside, false};
  if (snum == uncertain_lane) return std::nullopt;
  return TriangleClassification{snum == sden ? TriangleRelation::hit : TriangleRelation::behind,
                                TriangleLocation::inside, true};
}

// The relation alone: the signs of πa, πb, πc and den from one stage-1 evaluation in lanes (lane 3: den
// directly, as a determinant of d and the edges b − a, c − a), num only for a line through the triangle.
// Certified by: proofs/triangle/TriangleCascadeTwins.v, `fast_relation_tri_correct` (its twin, run against this code
// and the public relation() by the differential runner, routine tri_fast_relation: every answer is
// docs/contract.md §6's under both rules).
// With `values`, a line through the triangle (hit or behind) also leaves there the stage-1 values of num and
// den (lane 3) it was decided from, for the nearest hit's comparisons (ray_triangle_stages.hpp,
// TriangleQuotientStage1).
[[gnu::always_inline]] inline std::optional<TracedTriangleClassification> fast_relation(
    const Ray& ray, const Triangle& triangle, TriangleQuotientStage1* values = nullptr) noexcept {
  const TriangleLanes<FilterTerm<Lanes4>> s1 = triangle_relation_lanes(ray, triangle);
  // The proved stage-1 sign of each lane (the π constant holds for lane 3, see triangle_relation_lanes).
  const Mask4 sign = det3_filter_lanes(s1.lanes, bounds::triangle_filter_pi_relative, s1.absolute);
  const std::int64_t sa = sign[0], sb = sign[1], sc = sign[2], sden = sign[3];
  const bool certain = (sa != uncertain_lane) & (sb != uncertain_lane) & (sc != uncertain_lane) &
                       (sden != uncertain_lane);
  if (certain) [[likely]] {
    const bool inside = (sa == sden) & (sb == sden) & (sc == sden);
    if (!inside) return TracedTriangleClassification{{TriangleRelation::miss, TriangleLocation::outside, false}, Stage::filter};
    const InsideRelation through = inside_relation(ray, triangle, lane(s1.lanes, 3), s1.absolute[3]);
    if (values != nullptr) *values = through.values;
    if (through.num_sign != uncertain_lane)
      return TracedTriangleClassification{through.classification(sden), Stage::filter};
  }
  return std::nullopt;
}

}  // namespace

// ---- The full cascade --------------------------------------------------------------------------------------

// Stages 1–3 of the whole cascade run in the multiversioned functions below (noexcept: core/multiversion.hpp); the
// relation's is flattened (everything it calls inlined, so that its FMA clone computes every TwoProduct with the
// instruction instead of calling libm's fma: −16% on the degenerate workload; flattening the intersection's, whose
// time is stage 3's sums, measured no gain and tripled the file's compile time); the exact stage, which allocates, runs in
// their callers when they say what is left to it.
enum class ExactStageNeeded { none, relation, roundings };

RAYKERNEL_MULTIVERSION
ExactStageNeeded triangle_intersection_stages(const Ray& ray, const Triangle& triangle, const TriangleOptions& options,
                                              const TriangleStage2Handover* stage2, TracedTriangleIntersection& r) noexcept {
  TriangleCascade query = stage2 != nullptr && stage2->computed ? TriangleCascade(ray, triangle, stage2->values)
                                                                : TriangleCascade(ray, triangle);
  const std::optional<TriangleClassification> classified = query.classify(options.rule);
  if (!classified) return ExactStageNeeded::relation;
  const Stage relation_stage = query.stage();
  r = {answer(*classified), relation_stage, relation_stage};
  if (classified->location == TriangleLocation::none || (!options.t && !options.barycentric)) return ExactStageNeeded::none;

  // The quotients: an exactly zero numerator gives +0; the others are rounded from the stage-2 enclosures,
  // then from stage 3's, or else exactly.
  const bool asked[4] = {options.t, options.barycentric, options.barycentric, options.barycentric};
  int numerator_sign[4] = {0, 0, 0, 0};
  for (int k = 0; k < 4; ++k)
    if (asked[k]) numerator_sign[k] = query.sign(numerator_value[k]);
  if (query.needs_exact()) return ExactStageNeeded::roundings;
  bool certain[4];
  bool all_certain = true;
  double value[4];
  for (int k = 0; k < 4; ++k) {
    certain[k] = !asked[k] | (numerator_sign[k] == 0);  // bitwise: no branch on the data
    all_certain = all_certain & certain[k];
    value[k] = asked[k] ? 0.0 : not_a_number;  // an exact 0/den is +0
  }
  r.rounding_stage = query.stage();
  auto with_values = [&] {
    r.intersection.t = value[0];
    r.intersection.barycentric = {value[1], value[2], value[3]};
    return ExactStageNeeded::none;
  };
  if (all_certain) return with_values();

  // Stage 2: round_quotient on the enclosures, over one divisor.
  r.rounding_stage = query.reach(Stage::compensated);
  const TriangleCompensatedValues& s2 = query.compensated();
  Enclosure numerators[4];
  for (int k = 0; k < 4; ++k) numerators[numerator_lane[k]] = s2.enclosure(numerator_value[k]);
  const FourQuotients rounded = round_quotients(enclosure_lanes(numerators), s2.enclosure(value_den));
  all_certain = true;
  for (int k = 0; k < 4; ++k) {
    if (certain[k]) continue;
    value[k] = rounded.t[numerator_lane[k]];
    certain[k] = rounded.certain[numerator_lane[k]];
    all_certain = all_certain & certain[k];
  }
  if (all_certain) return with_values();

  // Stage 3: round_quotient on the expansions' tail enclosures over one divisor (den's tail enclosure, or
  // stage 2's when den's expansion is too long), then the exact stage for what is left (exact ties among it).
  r.rounding_stage = query.reach(Stage::expansion);
  const std::optional<Enclosure> den = query.expansion_enclosure(value_den);
  const Divisor divisor = prepare_divisor(den ? *den : s2.enclosure(value_den));
  all_certain = true;
  for (int k = 0; k < 4; ++k) {
    if (certain[k]) continue;
    if (const std::optional<Enclosure> n = query.expansion_enclosure(numerator_value[k])) {
      const QuotientRounding e = round_quotient(*n, divisor);
      value[k] = e.t;
      certain[k] = e.certain;
    }
    all_certain = all_certain & certain[k];
  }
  // Then the rounding boundaries of each candidate, exactly in expansions (core/quotient_boundary.hpp): a
  // quotient on or next to a midpoint between two doubles (ties, roundings near powers of two).
  if (!all_certain) {
    const std::optional<Expansion<16>> den_short = query.short_expansion<16>(value_den);
    const Sign den_sign = query.stage3_sign(value_den);
    all_certain = true;
    for (int k = 0; k < 4; ++k) {
      if (certain[k]) continue;
      if (den_short && (den_sign == Sign::positive || den_sign == Sign::negative)) {
        if (const std::optional<Expansion<16>> n = query.short_expansion<16>(numerator_value[k])) {
          if (const std::optional<double> q =
                  round_quotient_near(*n, *den_short, static_cast<int>(den_sign), value[k])) {
            value[k] = *q;
            certain[k] = true;
          }
        }
      }
      all_certain = all_certain & certain[k];
    }
  }
  // What is left goes to the exact stage, which rounds every asked quotient (the ones certified here are the
  // same correctly rounded values).
  if (!all_certain) return ExactStageNeeded::roundings;
  return with_values();
}

RAYKERNEL_MULTIVERSION_FLATTEN
std::optional<TracedTriangleClassification> triangle_relation_stages(const Ray& ray, const Triangle& triangle,
                                                                     TriangleRule rule) noexcept {
  TriangleCascade query(ray, triangle);
  if (const std::optional<TriangleClassification> c = query.classify(rule)) return TracedTriangleClassification{*c, query.stage()};
  return std::nullopt;
}

namespace {
TracedTriangleIntersection intersection_cascade(const Ray& ray, const Triangle& triangle, const TriangleOptions& options,
                                                const TriangleStage2Handover* stage2) {
  TracedTriangleIntersection r{};
  switch (triangle_intersection_stages(ray, triangle, options, stage2, r)) {
    case ExactStageNeeded::none: return r;
    case ExactStageNeeded::relation:
      return {exact::intersect_triangle(ray, triangle, options), Stage::exact, Stage::exact};
    case ExactStageNeeded::roundings: break;
  }
  const exact::TriangleRoundings e = exact::round_triangle_quotients(ray, triangle, options.t, options.barycentric);
  r.intersection.t = e.t;
  r.intersection.barycentric = e.barycentric;
  r.rounding_stage = Stage::exact;
  return r;
}
}  // namespace

TracedTriangleIntersection triangle_intersection_cascade(const Ray& ray, const Triangle& triangle,
                                                         const TriangleOptions& options) {
  return intersection_cascade(ray, triangle, options, nullptr);
}

TracedTriangleIntersection triangle_intersection_cascade(const Ray& ray, const Triangle& triangle,
                                                         const TriangleOptions& options,
                                                         const TriangleStage2Handover& stage2) {
  return intersection_cascade(ray, triangle, options, &stage2);
}

TracedTriangleClassification triangle_relation_cascade(const Ray& ray, const Triangle& triangle, TriangleRule rule) {
  if (const std::optional<TracedTriangleClassification> c = triangle_relation_stages(ray, triangle, rule)) return *c;
  return {exact::classify_triangle(ray, triangle, rule), Stage::exact};
}

// ---- The fast paths (multiversioned: noexcept, nothing here throws) ----------------------------------------

RAYKERNEL_MULTIVERSION
std::optional<TracedTriangleClassification> fast_triangle_relation(const Ray& ray, const Triangle& triangle,
                                                                   TriangleRule) noexcept {
  return fast_relation(ray, triangle);  // what it certifies has no π = 0: the rules agree
}

RAYKERNEL_MULTIVERSION
std::optional<TracedTriangleClassification> fast_triangle_relation(const Ray& ray, const Triangle& triangle,
                                                                   TriangleRule, TriangleQuotientStage1& values) noexcept {
  return fast_relation(ray, triangle, &values);
}

namespace {
// The body of fast_triangle_intersection, outside the multiversioned function: clang (14) rejects a call
// that passes a 256-bit vector (Lanes4) by value from a target_clones("fma") clone to a function without
// that target ("changes the ABI"), even an always_inline one; from this always_inline function, which the
// clones inline, no such call is made across targets. Everything it calls is always_inline too.
// Certified by: proofs/triangle/TriangleIntersectTheorem.v, `fast_intersection_tri_correct` (its twin, run against this
// code and the public intersect_traced() and intersect() by the differential runner, routine
// tri_fast_intersect: every answer is docs/contract.md §6's under both rules, t = RN(num/den), each
// barycentric RN(π_k/den)).
[[gnu::always_inline]] inline std::optional<TracedTriangleIntersection> fast_triangle_intersection_body(
    const Ray& ray, const Triangle& triangle, const TriangleOptions& options, TriangleStage2Handover* stage2) noexcept {
  if (!options.t && !options.barycentric) {
    const std::optional<TracedTriangleClassification> c = fast_relation(ray, triangle);
    if (!c) return std::nullopt;
    return TracedTriangleIntersection{answer(c->classification), c->stage, c->stage};
  }
  // Stages 1 and 2 of the π's and num in one Lanes4 evaluation; den summed from the lanes.
  const TriangleLanes<CompensatedTerm<Lanes4>> s2 = triangle_compensated_lanes(ray, triangle);
  const CompensatedTerm<double> den = (lane(s2.lanes, 0) + lane(s2.lanes, 1)) + lane(s2.lanes, 2);
  const double absolute_d = s2.absolute[0];
  const Mask4 filter = det3_filter_lanes(filter_view(s2.lanes), filter_relative_lanes, s2.absolute);
  const EnclosureT<Lanes4> numerators = det3_enclosure(s2.lanes, bounds::triangle_compensated_relative, s2.absolute);
  const Mask4 sign = first_certain_lanes(filter, enclosure_sign_lanes(numerators));
  const std::int64_t den_filter = det3_filter_lanes(filter_view(den), bounds::triangle_filter_den_relative, absolute_d);
  const Enclosure den_enclosure = det3_enclosure(den, bounds::triangle_compensated_den_relative, absolute_d);
  const std::int64_t den_sign = first_certain_lanes(den_filter, enclosure_sign_lanes(den_enclosure));
  const bool certain = (sign[0] != uncertain_lane) & (sign[1] != uncertain_lane) & (sign[2] != uncertain_lane) &
                       (den_sign != uncertain_lane);
  // Nothing certified: stage 2's values go to the cascade (den is summed there as here, (πa + πb) + πc).
  auto hand_over = [&] {
    if (stage2 != nullptr) *stage2 = {triangle_compensated_values_of(s2), true};
    return std::nullopt;
  };
  if (!certain) [[unlikely]]
    return hand_over();
  const std::optional<TriangleClassification> c = decide_nonzero(sign[0], sign[1], sign[2], den_sign, sign[lane_num]);
  // t needs num's sign to be certain (then nonzero): otherwise num may be exactly 0.
  if (!c || (options.t && sign[lane_num] == uncertain_lane)) [[unlikely]]
    return hand_over();
  const FourQuotients q = round_quotients(numerators, den_enclosure);
  const bool rounded = (!options.t || q.certain[lane_num]) &
                       (!options.barycentric || (q.certain[0] & q.certain[1] & q.certain[2]));
  if (!rounded) [[unlikely]]
    return hand_over();
  const bool by_filter = (filter[0] != uncertain_lane) & (filter[1] != uncertain_lane) &
                         (filter[2] != uncertain_lane) & (den_filter != uncertain_lane) &
                         (c->location == TriangleLocation::outside || filter[lane_num] != uncertain_lane);
  const double t = options.t ? q.t[lane_num] : not_a_number;
  const Barycentric u = options.barycentric ? Barycentric{q.t[0], q.t[1], q.t[2]}
                                            : Barycentric{not_a_number, not_a_number, not_a_number};
  return TracedTriangleIntersection{{c->relation, c->location, c->owned, t, u},
                                    by_filter ? Stage::filter : Stage::compensated, Stage::compensated};
}
}  // namespace

RAYKERNEL_MULTIVERSION
std::optional<TracedTriangleIntersection> fast_triangle_intersection(const Ray& ray, const Triangle& triangle,
                                                                     const TriangleOptions& options) noexcept {
  return fast_triangle_intersection_body(ray, triangle, options, nullptr);
}

RAYKERNEL_MULTIVERSION
std::optional<TracedTriangleIntersection> fast_triangle_intersection(const Ray& ray, const Triangle& triangle,
                                                                     const TriangleOptions& options,
                                                                     TriangleStage2Handover& stage2) noexcept {
  return fast_triangle_intersection_body(ray, triangle, options, &stage2);
}

}  // namespace raykernel::detail
