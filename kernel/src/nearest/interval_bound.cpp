// The interval test of one plane or one triangle on its own (nearest/interval_bound.hpp): the nearest-hit
// module's candidate of the primitive — its relation from the certified cascade — and within_interval, or, for the
// exact references, rationals.
#include "nearest/interval_bound.hpp"

#include "core/dot3_filter.hpp"
#include "core/error_bounds.hpp"
#include "nearest/exact_nearest.hpp"
#include "nearest/plane_candidate.hpp"
#include "nearest/triangle_candidate.hpp"
#include "occlusion/exact_occlusion.hpp"

#include <cmath>

namespace raykernel::detail {

std::optional<double> hit_t_within_interval(const Ray& ray, const RayInterval& interval, const Plane& plane) {
  const double o[3] = {ray.origin.x, ray.origin.y, ray.origin.z};
  const double d[3] = {ray.direction.x, ray.direction.y, ray.direction.z};
  const double n[3] = {plane.normal.x, plane.normal.y, plane.normal.z};
  const double diff[3] = {plane.point.x - o[0], plane.point.y - o[1], plane.point.z - o[2]};
  HitCandidate c(0, ray, plane, dot3_rounded(d, n), dot3_rounded(diff, n));
  if (c.decide_signs(dot3_filter_lanes(c.den, bounds::filter_den_relative),
                     dot3_filter_lanes(c.num, bounds::filter_num_relative)) != Relation::hit ||
      !within_interval(ray, c, interval))
    return std::nullopt;
  return c.round_t();
}

bool hits_within_interval(const Ray& ray, const RayInterval& interval, const Triangle& triangle, TriangleRule rule) {
  TriangleCandidate c;
  c.classify(ray, triangle, 0, 0, rule);
  return c.classification.relation == TriangleRelation::hit && within_interval(ray, c, interval);
}

namespace {
// t ∈ [t_min, t_max] for a hit (t ≥ 0), from the exact sign of t − b.
template <class Compare>
bool within_bounds(const RayInterval& interval, const Compare& compare_with) {
  if (interval.t_min > 0 && compare_with(interval.t_min) < 0) return false;
  return std::isinf(interval.t_max) || compare_with(interval.t_max) <= 0;  // (a valid t_max is not −inf)
}
}  // namespace

bool exact_t_within_interval(const Ray& ray, const RayInterval& interval, const Plane& plane) {
  return within_bounds(interval, [&](double b) { return exact::compare_plane_t_with(ray, plane, b); });
}
bool exact_t_within_interval(const Ray& ray, const RayInterval& interval, const Triangle& triangle) {
  return within_bounds(interval, [&](double b) { return exact::compare_triangle_t_with(ray, triangle, b); });
}

}  // namespace raykernel::detail
