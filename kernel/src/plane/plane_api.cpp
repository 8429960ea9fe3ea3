// The public ray–plane entry points: the default floating-point environment for the call
// (fp_environment.hpp), the fast path on raw input (for `intersect` also the second level's rounding of t, proved to
// answer only valid input), and — for what they do not certify — validation at the boundary (validation.hpp) and
// the rest of the cascade from the same per-query state (plane/ray_plane_stages.hpp); or the exact reference; or the
// naive baseline.
#include <raykernel/raykernel.hpp>

#include "core/fp_requirements.hpp"
#include "core/multiversion.hpp"
#include "plane/ray_plane_cascade.hpp"
#include "plane/exact_plane.hpp"
#include "core/fp_environment.hpp"
#include "core/fp_probe.hpp"
#include "plane/ray_plane_formula.hpp"
#include "core/validation.hpp"
#include "nearest/interval_bound.hpp"

#include <limits>
#include <optional>
#include <string>

namespace raykernel {
namespace {

void throw_if_invalid(const Ray& ray, const Plane& plane) {
  if (detail::is_valid(ray) & detail::is_valid(plane)) [[likely]]
    return;
  throw invalid_input(*validate(ray, plane));
}

// The multiversioned functions below (core/multiversion.hpp) never throw: GCC 12 treats a
// target_clones function as nothrow, so its callers would skip their cleanups (here: restoring the
// caller's floating-point environment) if an exception passed through one. Validation, which throws, is
// done between them.

// What the fast path did not certify: nothing for invalid input (which the caller reports), else the cascade's
// answer. Out of line, so that the fast path stays small: it is multiversioned, and a caller's clone calls its
// clone (GCC does not inline it; clang rejects noinline beside target_clones).
// First, on the raw input, stage 2's second level from the fast path's stage 1, without building the cascade:
// the signs stage 1 left open from that level, and t rounded on it (degenerate input: num or den cancels to a
// few ulps of its terms, so the first level is too wide to round t, and often to sign it). When both signs are
// certain and t rounds, the input is valid and that is the cascade's answer (a certified sign is the exact one,
// and t = RN(num/den) is unique); tests/plane_stages_test.cpp compares them, and the differential runner
// compares `intersect` with the cascade's twin. The fast path comes here straight after stage 1 when stage 1
// left a sign open (without stage 2's first level: `first_level` null), or after the first level when that did
// not round t (both signs then certain by stage 1). On bench's degenerate mix: 644 → 467 instructions a query
// (bench/README.md).
//   Certified by: proofs/plane/PlaneCascadeTwins.v, `second_level_twin_correct` (for every bit pattern: when the
//   step answers, the input passes validation, the relation is docs/contract.md §1's and t = RN(num/den)).
// Otherwise validation, then the cascade, from the fast path's values and its rounding of t on the first level
// when it got that far (GCC stores the values before the branch: +10 instructions on the certain path, −101 on
// this one), else from the inputs.
RAYKERNEL_MULTIVERSION std::optional<Intersection> intersection_rest(const Ray& ray, const Plane& plane,
                                                                     const detail::RayPlaneFastValues& values,
                                                                     detail::Mask2 filter,
                                                                     const detail::QuotientRounding* first_level) noexcept {
  const detail::EnclosureT<detail::Lanes2> refined = detail::refined_pair(values.stage1, ray, plane);
  const detail::Mask2 signs = detail::filter_or_refined_signs(filter, refined);
  if ((signs[0] != detail::uncertain_lane) & (signs[1] != detail::uncertain_lane)) {
    if (const auto t = detail::round_quotient_if_certain(detail::enclosure_lane(refined, 1),
                                                         detail::prepare_divisor(detail::enclosure_lane(refined, 0))))
      return Intersection{detail::signs_say_behind(signs[1], signs[0]) ? Relation::behind : Relation::hit, *t};
  }
  if (!(detail::is_valid(ray) & detail::is_valid(plane))) return std::nullopt;
  if (first_level == nullptr) {
    detail::RayPlaneCascade query(ray, plane);
    return detail::intersect_cascade(query).intersection;
  }
  detail::RayPlaneCascade query(ray, plane, values, *first_level);
  return detail::intersect_cascade(query).intersection;
}

[[gnu::noinline]] std::optional<Relation> relation_rest(const Ray& ray, const Plane& plane) noexcept {
  if (!(detail::is_valid(ray) & detail::is_valid(plane))) return std::nullopt;
  detail::RayPlaneCascade query(ray, plane);
  const detail::CertifiedSigns signs = detail::certified_signs(query);
  return detail::relation_from_signs(static_cast<int>(signs.num), static_cast<int>(signs.den));
}

// The whole certified path for one query, in the default environment: the fast path (left after stage 1 when
// that leaves a sign open), then the rest.
RAYKERNEL_MULTIVERSION
std::optional<Intersection> certified_intersection(const Ray& ray, const Plane& plane) noexcept {
  RAYKERNEL_QUERY_ARRAYS(ray, plane);
  detail::RayPlaneFastValues values;
  detail::Lanes2 alpha[3], b[3];
  const detail::Mask2 filter = detail::fast_stage1(o, d, p, n, values, alpha, b);
  if ((filter[0] == detail::uncertain_lane) | (filter[1] == detail::uncertain_lane)) [[unlikely]]
    return intersection_rest(ray, plane, values, filter, nullptr);
  const detail::FastAnswer a = detail::fast_answer_after_stage1(filter, alpha, b, values);
  if (a.certain) [[likely]]
    return Intersection{a.behind ? Relation::behind : Relation::hit, a.t};
  const detail::QuotientRounding first_level{a.t, a.rounding_certain};
  return intersection_rest(ray, plane, values, filter, &first_level);
}

RAYKERNEL_MULTIVERSION
std::optional<Relation> certified_relation(const Ray& ray, const Plane& plane) noexcept {
  const detail::FastRelationT<double> r = detail::fast_relation(ray, plane);
  if (r.certain) [[likely]]
    return r.behind ? Relation::behind : Relation::hit;
  return relation_rest(ray, plane);
}

}  // namespace

bool floating_point_environment_is_default() noexcept { return detail::fp_environment_is_default(); }

Intersection intersect(const Ray& ray, const Plane& plane) {
  const std::optional<Intersection> a = detail::in_default_fp_environment([&] { return certified_intersection(ray, plane); });
  if (!a) [[unlikely]]
    throw invalid_input(*validate(ray, plane));
  return *a;
}

Relation relation(const Ray& ray, const Plane& plane) {
  const std::optional<Relation> r = detail::in_default_fp_environment([&] { return certified_relation(ray, plane); });
  if (!r) [[unlikely]]
    throw invalid_input(*validate(ray, plane));
  return *r;
}

// The cascade stage by stage (filter first), so that the stages it reports are the cascade's, not the
// fused fast path's.
TracedIntersection intersect_traced(const Ray& ray, const Plane& plane) {
  return detail::in_default_fp_environment([&] {
    throw_if_invalid(ray, plane);
    detail::RayPlaneCascade query(ray, plane);
    return detail::intersect_cascade(query);
  });
}

Intersection intersect_exact(const Ray& ray, const Plane& plane) {
  return detail::in_default_fp_environment([&] {
    throw_if_invalid(ray, plane);
    return detail::exact::intersect(ray, plane);
  });
}

std::optional<Intersection> intersect(const Ray& ray, const RayInterval& interval, const Plane& plane) {
  return detail::in_default_fp_environment([&]() -> std::optional<Intersection> {
    throw_if_invalid(ray, plane);
    detail::throw_if_invalid_interval(interval);
    const std::optional<double> t = detail::hit_t_within_interval(ray, interval, plane);
    if (!t) return std::nullopt;
    return Intersection{Relation::hit, *t};
  });
}

std::optional<Intersection> intersect_exact(const Ray& ray, const RayInterval& interval, const Plane& plane) {
  return detail::in_default_fp_environment([&]() -> std::optional<Intersection> {
    throw_if_invalid(ray, plane);
    detail::throw_if_invalid_interval(interval);
    const Intersection x = detail::exact::intersect(ray, plane);
    if (x.relation != Relation::hit || !detail::exact_t_within_interval(ray, interval, plane)) return std::nullopt;
    return x;
  });
}

ExactIntersection intersect_exact_rational(const Ray& ray, const Plane& plane) {
  return detail::in_default_fp_environment([&] {
    throw_if_invalid(ray, plane);
    return detail::exact::intersect_rational(ray, plane);
  });
}

// The seed's formula in the caller's environment, as the baseline it is (no guarantee, no check).
Intersection intersect_naive(const Ray& ray, const Plane& plane) noexcept {
  const auto [num, den] = detail::ray_plane_values<double>(ray, plane, [](double x) { return x; });
  if (den == 0) return {num == 0 ? Relation::in_plane : Relation::parallel, std::numeric_limits<double>::quiet_NaN()};
  const double t = num / den;
  return {t >= 0 ? Relation::hit : Relation::behind, t};
}

std::string_view to_string(Relation relation) noexcept {
  switch (relation) {
    case Relation::hit: return "hit";
    case Relation::behind: return "behind";
    case Relation::parallel: return "parallel";
    case Relation::in_plane: return "in-plane";
  }
  return "?";
}

std::string_view to_string(Stage stage) noexcept {
  switch (stage) {
    case Stage::filter: return "filter";
    case Stage::compensated: return "compensated";
    case Stage::expansion: return "expansion";
    case Stage::exact: return "exact";
  }
  return "?";
}

std::string_view version() noexcept { return RAYKERNEL_VERSION; }

}  // namespace raykernel

namespace raykernel::detail {

// a·a − c as the kernel's compiler flags evaluate it. With -ffp-contract=off it is RN(RN(a·a) − c); a
// build that contracts it into one FMA returns the exact a·a − c instead. tests/fp_environment_test.cpp
// calls it with a = 1 + 2^-30, c = 1 + 2^-29, where the two differ (0 versus 2^-60).
double contraction_probe(double a, double c) noexcept { return a * a - c; }

}  // namespace raykernel::detail
