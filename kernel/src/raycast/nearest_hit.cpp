// nearest_hit: the plane with the smallest exact t among those a ray hits (docs/contract.md §4), by the certified
// cascade for each plane's relation and the certified comparison of t values (compare_quotients.hpp).
//
// Only the relation of each plane is decided in the loop (signs of num and den, stage 1 for almost every
// plane); t is rounded once, for the winner. The best plane so far keeps its cascade state, so the stages 2
// and 3 it computed for one comparison serve the next ones and the final rounding of t.
#include <raykernel/nearest_hit.hpp>

#include "certified/compare_quotients.hpp"
#include "certified/fp_requirements.hpp"
#include "certified/intersect_certified.hpp"
#include "certified/ray_plane_stages.hpp"
#include "exact/exact.hpp"
#include "exact/exact_compare.hpp"
#include "raycast/nearest_hit_internal.hpp"
#include "ray_plane_formula.hpp"

#include <cmath>
#include <cstring>
#include <optional>
#include <string>

namespace raykernel {
namespace detail {
namespace {

[[nodiscard]] Sign sign_of(int s) noexcept { return s < 0 ? Sign::negative : (s > 0 ? Sign::positive : Sign::zero); }

[[nodiscard]] bool same_bits(const Plane& a, const Plane& b) noexcept { return std::memcmp(&a, &b, sizeof(Plane)) == 0; }

[[nodiscard]] bool finite(const Vec3& v) noexcept {
  return (v.x - v.x) + (v.y - v.y) + (v.z - v.z) == 0;  // x − x is NaN for ±inf and NaN
}
[[nodiscard]] bool nonzero(const Vec3& v) noexcept { return v.x != 0 || v.y != 0 || v.z != 0; }

constexpr Ray valid_ray{{0, 0, 0}, {1, 0, 0}};
constexpr Plane valid_plane{{0, 0, 0}, {1, 0, 0}};

void throw_if_invalid(const Ray& ray, std::span<const Plane> planes) {
  if (!(finite(ray.origin) && finite(ray.direction) && nonzero(ray.direction))) {
    if (std::optional<std::string> reason = validate(ray, valid_plane)) throw invalid_input(*reason);
  }
  for (std::size_t k = 0; k < planes.size(); ++k) {
    const Plane& p = planes[k];
    if (finite(p.point) && finite(p.normal) && nonzero(p.normal)) continue;
    if (std::optional<std::string> reason = validate(valid_ray, p))
      throw invalid_input("plane " + std::to_string(k) + ": " + *reason);
  }
}

[[nodiscard]] Stage slower(Stage a, Stage b) noexcept { return a > b ? a : b; }

}  // namespace

RAYKERNEL_MULTIVERSION
DistanceOrder compare_hit_distances(HitCandidate& a, HitCandidate& b) {
  // t = 0 exactly (the origin on the plane) comes first; num's sign is exact.
  const bool a_at_origin = a.num_sign == Sign::zero, b_at_origin = b.num_sign == Sign::zero;
  if (a_at_origin || b_at_origin) return {static_cast<int>(!a_at_origin) - static_cast<int>(!b_at_origin), Stage::filter};
  // The same doubles give the same exact t.
  if (same_bits(a.stages.plane(), b.stages.plane())) return {0, Stage::filter};

  // sign(t_a − t_b) = sign(Δ)·sign(den_a)·sign(den_b).
  const int orientation = a.den_sign == b.den_sign ? 1 : -1;
  RayPlaneStages& qa = a.stages;
  RayPlaneStages& qb = b.stages;

  Sign delta = compare_quotients_filter(filter_enclosure(qa.num_rounded(), bounds::filter_num_relative),
                                        filter_enclosure(qa.den_rounded(), bounds::filter_den_relative),
                                        filter_enclosure(qb.num_rounded(), bounds::filter_num_relative),
                                        filter_enclosure(qb.den_rounded(), bounds::filter_den_relative));
  if (is_certain(delta)) return {orientation * static_cast<int>(delta), Stage::filter};

  delta = enclosure_sign(compare_quotients_compensated(qa.num_compensated(), qa.den_compensated(),
                                                       qb.num_compensated(), qb.den_compensated()));
  if (is_certain(delta)) return {orientation * static_cast<int>(delta), Stage::compensated};

  delta = compare_quotients_expansion(qa.expansions(), qb.expansions());
  if (is_certain(delta)) return {orientation * static_cast<int>(delta), Stage::expansion};

  return {orientation * exact::compare_quotients(qa.ray(), qa.plane(), qb.plane()), Stage::exact};
}

namespace {

RAYKERNEL_MULTIVERSION
TracedNearestHit nearest_hit_certified_valid(const Ray& ray, std::span<const Plane> planes) {
  TracedNearestHit trace;
  // Two slots: the best candidate so far and the one being examined, so neither is ever copied.
  std::optional<HitCandidate> slot[2];
  int best = -1;
  for (std::size_t k = 0; k < planes.size(); ++k) {
    const int current = best == 0 ? 1 : 0;
    HitCandidate& candidate = slot[current].emplace(k, ray, planes[k]);
    if (const std::optional<CertifiedSigns> signs = certified_signs(candidate.stages)) {
      candidate.num_sign = signs->num;
      candidate.den_sign = signs->den;
      candidate.relation_stage = signs->stage;
    } else {  // stage 3 was not exact: the exact stage decides
      const exact::ExactSigns exact_signs = exact::ray_plane_signs(ray, planes[k]);
      candidate.num_sign = sign_of(exact_signs.num);
      candidate.den_sign = sign_of(exact_signs.den);
    }
    trace.relation_stage = slower(trace.relation_stage, candidate.relation_stage);
    const Relation relation =
        relation_from_signs(static_cast<int>(candidate.num_sign), static_cast<int>(candidate.den_sign));
    if (relation != Relation::hit) continue;
    if (best < 0) {
      best = current;
      continue;
    }
    const DistanceOrder order = compare_hit_distances(candidate, *slot[best]);
    ++trace.comparisons[static_cast<std::size_t>(order.stage)];
    trace.comparison_stage = slower(trace.comparison_stage, order.stage);
    if (order.sign < 0) best = current;  // strictly nearer; a tie keeps the smaller index
  }
  if (best < 0) return trace;

  HitCandidate& winner = *slot[best];
  if (winner.num_sign == Sign::zero) {
    trace.hit = NearestHit{winner.index, 0.0};  // exact zero: +0, decided with the relation
    trace.t_stage = winner.relation_stage;
    return trace;
  }
  const auto [t, t_stage] = certified_quotient(winner.stages);
  trace.hit = NearestHit{winner.index, t};
  trace.t_stage = t_stage;
  return trace;
}

}  // namespace
}  // namespace detail

std::optional<std::string> validate_plane(const Plane& plane) { return validate(detail::valid_ray, plane); }

std::optional<std::string> validate_ray(const Ray& ray) { return validate(ray, detail::valid_plane); }

TracedNearestHit nearest_hit_traced(const Ray& ray, std::span<const Plane> planes) {
  detail::throw_if_invalid(ray, planes);
  if (!floating_point_environment_is_default()) {
    TracedNearestHit trace;
    trace.relation_stage = trace.comparison_stage = trace.t_stage = Stage::exact;
    if (const std::optional<std::size_t> k = detail::exact::nearest_plane(ray, planes))
      trace.hit = NearestHit{*k, detail::exact::intersect(ray, planes[*k]).t};
    return trace;
  }
  return detail::nearest_hit_certified_valid(ray, planes);
}

std::optional<NearestHit> nearest_hit(const Ray& ray, std::span<const Plane> planes) {
  return nearest_hit_traced(ray, planes).hit;
}

std::optional<NearestHit> nearest_hit_exact(const Ray& ray, std::span<const Plane> planes) {
  detail::throw_if_invalid(ray, planes);
  const std::optional<std::size_t> k = detail::exact::nearest_plane(ray, planes);
  if (!k) return std::nullopt;
  return NearestHit{*k, detail::exact::intersect(ray, planes[*k]).t};
}

std::optional<NearestHit> nearest_hit_naive(const Ray& ray, std::span<const Plane> planes) noexcept {
  std::optional<NearestHit> best;
  for (std::size_t k = 0; k < planes.size(); ++k) {
    const Intersection r = intersect_naive(ray, planes[k]);
    if (r.relation != Relation::hit) continue;
    if (!best || r.t < best->t) best = NearestHit{k, r.t};
  }
  return best;
}

}  // namespace raykernel
