// The certified ray–plane query: the cascade filter → compensated → expansion → exact.
//
// The relation needs the exact signs of den = d·n and num = (p − o)·n; each stage is asked only for the
// signs the cheaper ones left uncertain. t needs a correct rounding of num/den: round_quotient decides it
// from the compensated enclosures, then from the (near-exact) expansion enclosures, and the exact stage
// settles what is left (exact ties, values within ~2^-100 of a rounding boundary, extreme exponents).
//
// The per-query state (inputs, stage 1, stages 2 and 3 on demand) lives in RayPlaneStages
// (certified/ray_plane_stages.hpp) so that nearest_hit can reuse it; the arithmetic and the order of the
// decisions are the ones the proofs follow.
//
// Certified by:
//   certified_signs, stages 1 and 2 (both levels):  proofs/Cascade.v, `cascade_signs_correct`
//   certified_quotient, stage 2 (both levels):      proofs/Cascade.v, `cascade_quotient_correct`
//   certified_quotient, stage 3 enclosures:         proofs/Cascade.v, `expansion_t_correct` (+ Shewchuk, cited)
//   intersect_certified before full_cascade:        proofs/Cascade.v, `intersect_fast_correct`
//
// The file is compiled with -ffp-contract=off and without fast-math (kernel/CMakeLists.txt): the proofs
// model each + − × / as one correctly rounded operation and each std::fma as one rounding.
#include "certified/fp_requirements.hpp"
#include "certified/enclosure.hpp"
#include "certified/error_bounds.hpp"
#include "certified/expansion.hpp"
#include "certified/fast_path.hpp"
#include "certified/intersect_certified.hpp"
#include "certified/ray_plane_stages.hpp"
#include "certified/round_quotient.hpp"
#include "exact/exact.hpp"
#include "ray_plane_formula.hpp"

#include <cmath>
#include <limits>
#include <optional>
#include <string>

namespace raykernel::detail {
namespace {

constexpr double not_a_number = std::numeric_limits<double>::quiet_NaN();

[[nodiscard]] int to_int(Sign s) noexcept { return static_cast<int>(s); }

}  // namespace

// GCC and clang (≥ 14) build an FMA clone and a portable clone of these functions and pick one when the
// program loads: std::fma is one instruction in the first and a correctly rounded libm call in the
// second, so both compute the same bits.
RAYKERNEL_MULTIVERSION
std::optional<CertifiedSigns> certified_signs(RayPlaneStages& query) noexcept {
  // Stage 1: binary64 filter.
  Sign den_sign = dot3_filter(query.den_rounded(), bounds::filter_den_relative, query.den_trivially_zero());
  Sign num_sign = dot3_filter(query.num_rounded(), bounds::filter_num_relative, query.num_trivially_zero());
  Stage stage = Stage::filter;

  // Stage 2, computed on demand and kept for the rounding of t.
  if (!is_certain(den_sign) || !is_certain(num_sign)) {
    stage = Stage::compensated;
    if (!is_certain(den_sign)) den_sign = enclosure_sign(query.den_compensated());
    if (!is_certain(num_sign)) num_sign = enclosure_sign(query.num_compensated());
    // The second level of stage 2, for values that cancel to within ~2^-100 of the terms.
    if (!is_certain(den_sign)) den_sign = enclosure_sign(query.den_refined());
    if (!is_certain(num_sign)) num_sign = enclosure_sign(query.num_refined());
  }
  // Stage 3: exact signs, if the expansions are exact.
  if (!is_certain(den_sign) || !is_certain(num_sign)) {
    const ExactExpansions& e = query.expansions();
    if (!e.exact) return std::nullopt;
    stage = Stage::expansion;
    den_sign = e.den.sign();
    num_sign = e.num.sign();
  }
  return CertifiedSigns{num_sign, den_sign, stage};
}

RAYKERNEL_MULTIVERSION
std::pair<double, Stage> certified_quotient(RayPlaneStages& query) {
  if (const std::optional<double> t = round_quotient(query.num_compensated(), query.den_compensated()))
    return {*t, Stage::compensated};
  if (const std::optional<double> t = round_quotient(query.num_refined(), query.den_refined()))
    return {*t, Stage::compensated};
  const ExactExpansions& e = query.expansions();
  if (e.exact) {
    if (const std::optional<double> t =
            round_quotient(expansion_tail_enclosure(e.num), expansion_tail_enclosure(e.den)))
      return {*t, Stage::expansion};
  }
  return {exact::intersect(query.ray(), query.plane()).t, Stage::exact};
}

// The full cascade, for what the fast path did not certify: validation first (the fast path needs none),
// then stages 1–4 for the relation and for t.
[[gnu::noinline]] TracedIntersection full_cascade(const Ray& ray, const Plane& plane) {
  if (std::optional<std::string> reason = validate(ray, plane)) throw invalid_input(*reason);
  RayPlaneStages query(ray, plane);
  const std::optional<CertifiedSigns> signs = certified_signs(query);
  if (!signs) return {exact::intersect(ray, plane), Stage::exact, Stage::exact};

  const Relation relation = relation_from_signs(to_int(signs->num), to_int(signs->den));
  if (relation == Relation::parallel || relation == Relation::in_plane)
    return {{relation, not_a_number}, signs->stage, signs->stage};
  if (signs->num == Sign::zero) return {{Relation::hit, 0.0}, signs->stage, signs->stage};

  // t = RN(num/den), num ≠ 0 ≠ den.
  const auto [t, t_stage] = certified_quotient(query);
  return {{relation, t}, signs->stage, t_stage};
}

RAYKERNEL_MULTIVERSION
TracedIntersection intersect_certified(const Ray& ray, const Plane& plane) {
  const Vec3 &ro = ray.origin, &rd = ray.direction, &pp = plane.point, &pn = plane.normal;
  const double o[3] = {ro.x, ro.y, ro.z}, d[3] = {rd.x, rd.y, rd.z};
  const double p[3] = {pp.x, pp.y, pp.z}, n[3] = {pn.x, pn.y, pn.z};
  const FastQuery query(o, d, p, n);
  const FastQuery::FilterSigns signs = query.filter_signs();
  if (signs.decided()) [[likely]] {
    if (const QuotientRounding t = query.compensated_t(); t.certain) [[likely]]
      return {{signs.relation(), t.t}, Stage::filter, Stage::compensated};
  }
  // Near-degenerate (a value within ~2^-50 of its terms' magnitude), or t near a rounding boundary: the
  // second level of stage 2 settles both for condition numbers up to ~2^90.
  const FastAnswer refined = query.refined_answer();
  if (refined.relation_certain & refined.t_certain)
    return {{refined.behind ? Relation::behind : Relation::hit, refined.t},
            signs.decided() ? Stage::filter : Stage::compensated, Stage::compensated};
  return full_cascade(ray, plane);
}

}  // namespace raykernel::detail
